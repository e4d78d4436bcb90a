"""rclpy's ParameterService: the six ``rcl_interfaces`` services every node serves under its own
name (``<node>/get_parameters`` ...), so ``ros2 param`` and other nodes read and set its
parameters. On the Zenoh wire they are services like any other."""

from __future__ import annotations

import weakref
from typing import Any

from rcl_interfaces.msg import ListParametersResult, SetParametersResult
from rcl_interfaces.srv import (
    DescribeParameters,
    GetParameters,
    GetParameterTypes,
    ListParameters,
    SetParameters,
    SetParametersAtomically,
)

from rclpy.exceptions import ParameterNotDeclaredException, ParameterUninitializedException
from rclpy.parameter import Parameter
from rclpy.qos import qos_profile_parameters


class ParameterService:
    def __init__(self, node: Any) -> None:
        self._node_weak_ref = weakref.ref(node)
        name = node.get_name()
        for srv_type, suffix, callback in (
            (DescribeParameters, "describe_parameters", self._describe_parameters_callback),
            (GetParameters, "get_parameters", self._get_parameters_callback),
            (GetParameterTypes, "get_parameter_types", self._get_parameter_types_callback),
            (ListParameters, "list_parameters", self._list_parameters_callback),
            (SetParameters, "set_parameters", self._set_parameters_callback),
            (SetParametersAtomically, "set_parameters_atomically", self._set_parameters_atomically_callback),
        ):
            node.create_service(srv_type, f"{name}/{suffix}", callback, qos_profile=qos_profile_parameters)

    def _get_node(self) -> Any:
        node = self._node_weak_ref()
        if node is None:
            raise ReferenceError("Expected valid node weak reference")
        return node

    # An unknown name answers with an empty list, as rclpy's service does.
    def _describe_parameters_callback(self, request: Any, response: Any) -> Any:
        try:
            response.descriptors = self._get_node().describe_parameters(list(request.names))
        except ParameterNotDeclaredException:
            response.descriptors = []
        return response

    def _get_parameters_callback(self, request: Any, response: Any) -> Any:
        try:
            params = self._get_node().get_parameters(list(request.names))
        except (ParameterNotDeclaredException, ParameterUninitializedException):
            params = []
        response.values = [p.get_parameter_value() for p in params]
        return response

    def _get_parameter_types_callback(self, request: Any, response: Any) -> Any:
        try:
            response.types = self._get_node().get_parameter_types(list(request.names))
        except ParameterNotDeclaredException:
            response.types = []
        return response

    def _list_parameters_callback(self, request: Any, response: Any) -> Any:
        try:
            response.result = self._get_node().list_parameters(list(request.prefixes), int(request.depth))
        except (TypeError, ValueError):
            response.result = ListParametersResult()
        return response

    def _set_parameters_callback(self, request: Any, response: Any) -> Any:
        node = self._get_node()
        for msg in request.parameters:
            response.results.append(self._set(node, [Parameter.from_parameter_msg(msg)]))
        return response

    def _set_parameters_atomically_callback(self, request: Any, response: Any) -> Any:
        node = self._get_node()
        response.result = self._set(node, [Parameter.from_parameter_msg(m) for m in request.parameters])
        return response

    @staticmethod
    def _set(node: Any, params: list[Parameter]) -> SetParametersResult:
        try:
            return node.set_parameters_atomically(params)  # type: ignore[no-any-return]
        except ParameterNotDeclaredException as exc:
            return SetParametersResult(successful=False, reason=str(exc))


__all__ = ["ParameterService"]
