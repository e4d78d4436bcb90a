"""rclpy.action's graph queries: actions are found by their ``<action>/_action/send_goal`` services,
as rcl_action finds them, in this process and in the rest of the graph."""

from __future__ import annotations

from typing import Any

SEND_GOAL_SUFFIX = "/_action/send_goal"
SEND_GOAL_TYPE_SUFFIX = "_SendGoal"


def _action(service_name: str, type_name: str) -> tuple[str, str] | None:
    """(action name, action type) of an action's send_goal service; None for another service."""
    if not service_name.endswith(SEND_GOAL_SUFFIX) or not type_name.endswith(SEND_GOAL_TYPE_SUFFIX):
        return None
    return service_name[: -len(SEND_GOAL_SUFFIX)], type_name[: -len(SEND_GOAL_TYPE_SUFFIX)]


def _entries(node: Any, kind: str, node_fqn: str | None) -> list[tuple[str, list[str]]]:
    """``kind`` is "SS" (servers) or "SC" (clients); ``node_fqn`` limits them to one node's."""
    found: dict[str, set[str]] = {}
    for channel in node._bus.services.values():
        entities = channel.servers if kind == "SS" else channel.clients
        for entity in entities:
            if node_fqn is None or entity.node.fully_qualified_name == node_fqn:
                pair = _action(channel.name, channel.srv_type.TYPE)
                if pair is not None:
                    found.setdefault(pair[0], set()).add(pair[1])
    bridge = node._rcl_context.bridge
    if bridge is not None:
        for e in bridge.remote.endpoints():
            if e.kind == kind and (node_fqn is None or e.node == node_fqn):
                pair = _action(e.name, e.type_name)
                if pair is not None:
                    found.setdefault(pair[0], set()).add(pair[1])
    return sorted((name, sorted(types)) for name, types in found.items())


def _fqn(node_name: str, node_namespace: str) -> str:
    return node_namespace.rstrip("/") + "/" + node_name


def get_action_names_and_types(node: Any) -> list[tuple[str, list[str]]]:
    """Every action some node serves or calls: (name, [``pkg/action/Type``])."""
    merged: dict[str, set[str]] = {}
    for name, types in _entries(node, "SS", None) + _entries(node, "SC", None):
        merged.setdefault(name, set()).update(types)
    return sorted((name, sorted(types)) for name, types in merged.items())


def get_action_server_names_and_types_by_node(
    node: Any, remote_node_name: str, remote_node_namespace: str
) -> list[tuple[str, list[str]]]:
    return _entries(node, "SS", _fqn(remote_node_name, remote_node_namespace))


def get_action_client_names_and_types_by_node(
    node: Any, remote_node_name: str, remote_node_namespace: str
) -> list[tuple[str, list[str]]]:
    return _entries(node, "SC", _fqn(remote_node_name, remote_node_namespace))
