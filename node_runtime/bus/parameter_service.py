"""ROS 2's six parameter services for a bus node (``<node>/list_parameters``, ``get_parameters``,
``get_parameter_types``, ``describe_parameters``, ``set_parameters``,
``set_parameters_atomically``), answered from the node's own table, so ``ros2 param`` and other
nodes read and set the lab's own nodes as they do a node process's.

The executor runs each call as it runs any service callback, between the node's other callbacks
and within its pass's bound; every answer is one look-up per name a request carries (a set also
runs the node's on-set callback), so none holds the loop.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import partial
from typing import TYPE_CHECKING, Any

from node_runtime.bus.parameter_values import from_value_msg, to_value_msg, type_of
from node_runtime.bus.parameters import Parameter
from node_runtime.bus.services import ServiceServer
from node_runtime.msgs import Service
from node_runtime.msgs.generated.rcl_interfaces import (
    DescribeParameters,
    GetParameters,
    GetParameterTypes,
    ListParameters,
    ListParametersResult,
    SetParameters,
    SetParametersAtomically,
    SetParametersResult,
)

if TYPE_CHECKING:
    from node_runtime.bus.node import Node


def serve_parameters(node: Node) -> list[ServiceServer]:
    """Serve the six services under the node's name (none if it serves them already, as an rclpy
    node does); they go when the node is destroyed."""
    name = node.get_name()
    if any(s.channel.name == node.resolve_topic_name(f"{name}/list_parameters") for s in node.services):
        return []
    return [
        node.create_service(srv, f"{name}/{suffix}", partial(answer, node))
        for srv, suffix, answer in _SERVICES
    ]


def _declared(node: Node, names: list[str]) -> bool:
    """Whether every name is declared: rclpy answers a request naming any other with nothing."""
    return all(node.has_parameter(n) for n in names)


def _describe(node: Node, request: Any, response: Any) -> Any:
    names = list(request.names)
    response.descriptors = [node.describe_parameter(n) for n in names] if _declared(node, names) else []
    return response


def _get(node: Node, request: Any, response: Any) -> Any:
    names = list(request.names)
    if _declared(node, names):
        response.values = [to_value_msg(node.get_parameter(n).value) for n in names]
    return response


def _types(node: Node, request: Any, response: Any) -> Any:
    names = list(request.names)
    if _declared(node, names):
        response.types = [type_of(node.get_parameter(n).value) for n in names]
    return response


def _list(node: Node, request: Any, response: Any) -> Any:
    try:
        names, prefixes = node.list_parameter_names(list(request.prefixes), int(request.depth))
    except ValueError:
        return response
    response.result = ListParametersResult(names=names, prefixes=prefixes)
    return response


def _result(node: Node, messages: list[Any]) -> SetParametersResult:
    try:
        params = [Parameter(m.name, from_value_msg(m.value)) for m in messages]
        node.set_parameters(params)
    except (LookupError, ValueError) as exc:
        reason = str(exc.args[0]) if exc.args else type(exc).__name__
        return SetParametersResult(successful=False, reason=reason)
    return SetParametersResult(successful=True)


def _set(node: Node, request: Any, response: Any) -> Any:
    response.results = [_result(node, [m]) for m in request.parameters]
    return response


def _set_atomically(node: Node, request: Any, response: Any) -> Any:
    response.result = _result(node, list(request.parameters))
    return response


_SERVICES: tuple[tuple[type[Service], str, Callable[[Node, Any, Any], Any]], ...] = (
    (DescribeParameters, "describe_parameters", _describe),
    (GetParameters, "get_parameters", _get),
    (GetParameterTypes, "get_parameter_types", _types),
    (ListParameters, "list_parameters", _list),
    (SetParameters, "set_parameters", _set),
    (SetParametersAtomically, "set_parameters_atomically", _set_atomically),
)

__all__ = ["serve_parameters"]
