"""rclpy Node's graph queries by name and namespace: the nodes, the services, a node's publishers.
What this process's bus holds and, joined over Zenoh, what the rest of the graph's tokens say."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from rclpy._context import Context


def _split(fully_qualified: str) -> tuple[str, str]:
    """``/robot/talker`` as (``talker``, ``/robot``); ``/talker`` as (``talker``, ``/``)."""
    namespace, _, name = fully_qualified.rpartition("/")
    return name, namespace or "/"


def _remote_endpoints(context: Context) -> list[Any]:
    bridge = context.bridge
    return [] if bridge is None else bridge.remote.endpoints()


class GraphQueries:
    """Mixed into rclpy's Node (node.py), which has ``_bus`` and ``_rcl_context``."""

    _bus: Any
    _rcl_context: Context

    def get_node_names_and_namespaces(self) -> list[tuple[str, str]]:
        found = {(n.get_name(), n.get_namespace()) for n in self._bus.nodes}
        bridge = self._rcl_context.bridge
        if bridge is not None:
            found.update(_split(n.name) for n in bridge.remote.nodes())
        return sorted(found)

    def get_service_names_and_types(self) -> list[tuple[str, list[str]]]:
        found: dict[str, set[str]] = {
            name: {channel.srv_type.TYPE} for name, channel in self._bus.services.items()
        }
        for e in _remote_endpoints(self._rcl_context):
            if e.kind in ("SS", "SC"):
                found.setdefault(e.name, set()).add(e.type_name)
        return sorted((name, sorted(types)) for name, types in found.items())

    def get_publisher_names_and_types_by_node(
        self, node_name: str, node_namespace: str, no_demangle: bool = False
    ) -> list[tuple[str, list[str]]]:
        found: dict[str, set[str]] = {}
        for node in self._bus.nodes:
            if node.get_name() == node_name and node.get_namespace() == node_namespace:
                for pub in node.publishers:
                    found.setdefault(pub.topic_name, set()).add(pub.msg_type.TYPE)
        fully_qualified = node_namespace.rstrip("/") + "/" + node_name
        for e in _remote_endpoints(self._rcl_context):
            if e.kind == "MP" and e.node == fully_qualified:
                found.setdefault(e.name, set()).add(e.type_name)
        return sorted((name, sorted(types)) for name, types in found.items())
