"""rclpy's AsyncParameterClient: another node's parameter services, each call a Future of the
service's response (spin the node, or ``rclpy.spin_until_future_complete``, until it is done)."""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from typing import Any

from rcl_interfaces.msg import Parameter as ParameterMsg
from rcl_interfaces.msg import ParameterEvent
from rcl_interfaces.srv import (
    DescribeParameters,
    GetParameters,
    GetParameterTypes,
    ListParameters,
    SetParameters,
    SetParametersAtomically,
)

from node_runtime.bus import Future
from rclpy.callback_groups import CallbackGroup
from rclpy.parameter import Parameter, parameter_dict_from_yaml_file
from rclpy.qos import QoSProfile, qos_profile_parameter_events, qos_profile_services_default

WAIT_POLL_S = 0.02  # how often wait_for_services looks at the graph (rclpy sleeps 0.25 s)


def _as_msgs(parameters: Sequence[Parameter | ParameterMsg]) -> list[ParameterMsg]:
    return [p.to_parameter_msg() if isinstance(p, Parameter) else p for p in parameters]


class AsyncParameterClient:
    def __init__(
        self,
        node: Any,
        remote_node_name: str,
        qos_profile: QoSProfile = qos_profile_services_default,
        callback_group: CallbackGroup | None = None,
    ) -> None:
        self.remote_node_name = remote_node_name
        self.node = node

        def client(srv_type: Any, suffix: str) -> Any:
            return node.create_client(
                srv_type,
                f"{remote_node_name}/{suffix}",
                qos_profile=qos_profile,
                callback_group=callback_group,
            )

        self._get_parameter_client = client(GetParameters, "get_parameters")
        self._list_parameter_client = client(ListParameters, "list_parameters")
        self._set_parameter_client = client(SetParameters, "set_parameters")
        self._get_parameter_types_client = client(GetParameterTypes, "get_parameter_types")
        self._describe_parameters_client = client(DescribeParameters, "describe_parameters")
        self._set_parameters_atomically_client = client(SetParametersAtomically, "set_parameters_atomically")
        self._clients = (
            self._get_parameter_client,
            self._list_parameter_client,
            self._set_parameter_client,
            self._get_parameter_types_client,
            self._describe_parameters_client,
            self._set_parameters_atomically_client,
        )

    def services_are_ready(self) -> bool:
        return all(c.service_is_ready() for c in self._clients)

    def wait_for_services(self, timeout_sec: float | None = None) -> bool:
        """True once all six services are in the graph; False after ``timeout_sec``."""
        end = None if timeout_sec is None else time.monotonic() + timeout_sec
        for c in self._clients:
            left = None if end is None else max(0.0, end - time.monotonic())
            if not c.wait_for_service(left):
                return False
        return self.services_are_ready()

    @staticmethod
    def _call(client: Any, request: Any, callback: Callable[[Any], None] | None) -> Future[Any]:
        future: Future[Any] = client.call_async(request)
        if callback is not None:
            future.add_done_callback(callback)
        return future

    def list_parameters(
        self,
        prefixes: list[str] | None = None,
        depth: int | None = None,
        callback: Callable[[Any], None] | None = None,
    ) -> Future[Any]:
        request = ListParameters.Request()
        if prefixes:
            request.prefixes = list(prefixes)
        if depth:
            request.depth = depth
        return self._call(self._list_parameter_client, request, callback)

    def get_parameters(self, names: list[str], callback: Callable[[Any], None] | None = None) -> Future[Any]:
        return self._call(self._get_parameter_client, GetParameters.Request(names=list(names)), callback)

    def set_parameters(
        self, parameters: Sequence[Parameter | ParameterMsg], callback: Callable[[Any], None] | None = None
    ) -> Future[Any]:
        request = SetParameters.Request(parameters=_as_msgs(parameters))
        return self._call(self._set_parameter_client, request, callback)

    def describe_parameters(
        self, names: list[str], callback: Callable[[Any], None] | None = None
    ) -> Future[Any]:
        request = DescribeParameters.Request(names=list(names))
        return self._call(self._describe_parameters_client, request, callback)

    def get_parameter_types(
        self, names: list[str], callback: Callable[[Any], None] | None = None
    ) -> Future[Any]:
        request = GetParameterTypes.Request(names=list(names))
        return self._call(self._get_parameter_types_client, request, callback)

    def set_parameters_atomically(
        self, parameters: Sequence[Parameter | ParameterMsg], callback: Callable[[Any], None] | None = None
    ) -> Future[Any]:
        request = SetParametersAtomically.Request(parameters=_as_msgs(parameters))
        return self._call(self._set_parameters_atomically_client, request, callback)

    def delete_parameters(
        self, names: list[str], callback: Callable[[Any], None] | None = None
    ) -> Future[Any]:
        """Unset parameters (only dynamically typed ones can be)."""
        return self.set_parameters([Parameter(name) for name in names], callback)

    def load_parameter_file(
        self, parameter_file: str, use_wildcard: bool = False, callback: Callable[[Any], None] | None = None
    ) -> Future[Any]:
        params = parameter_dict_from_yaml_file(parameter_file, use_wildcard)
        return self.set_parameters(list(params.values()), callback)

    def load_parameter_file_atomically(
        self, parameter_file: str, use_wildcard: bool = False, callback: Callable[[Any], None] | None = None
    ) -> Future[Any]:
        params = parameter_dict_from_yaml_file(parameter_file, use_wildcard)
        return self.set_parameters_atomically(list(params.values()), callback)

    def on_parameter_event(
        self,
        callback: Callable[[ParameterEvent], None],
        qos_profile: QoSProfile = qos_profile_parameter_events,
        *,
        callback_group: CallbackGroup | None = None,
        **_: Any,
    ) -> Any:
        return self.node.create_subscription(
            ParameterEvent, "/parameter_events", callback, qos_profile, callback_group=callback_group
        )


__all__ = ["AsyncParameterClient"]
