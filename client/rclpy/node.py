"""``rclpy.node.Node`` for a node process: the lab's bus node, joined to the graph over Zenoh."""

from __future__ import annotations

from typing import Any

from server.bus import Node as BusNode
from server.bus import Parameter

from ._context import Context, default_context
from .rate import Rate


class Node(BusNode):
    """Subclass it as the handout does: ``super().__init__('KeyboardManagerNode')``."""

    def __init__(self, node_name: str, *, context: Context | None = None, **kwargs: Any) -> None:
        self._rcl_context = context or default_context
        bus, _executor = self._rcl_context.require()
        super().__init__(node_name, context=bus, **kwargs)
        self._warn_if_name_taken()

    def _warn_if_name_taken(self) -> None:
        bridge = self._rcl_context.bridge
        if bridge is None:
            return
        if any(n.name == self.fully_qualified_name for n in bridge.remote.nodes()):
            self.get_logger().warning(
                f"a node named {self.fully_qualified_name} already exists in the graph: ROS allows this, "
                "but tools and logs will mix the two up (give this one another name with -r __node:=NAME)"
            )

    def create_rate(self, frequency: float, clock: Any = None) -> Rate:
        return Rate(frequency, self._rcl_context)

    def get_node_names(self) -> list[str]:
        names = [n.get_name() for n in self.bus.nodes]
        bridge = self._rcl_context.bridge
        if bridge is not None:
            names += [n.name.rsplit("/", 1)[1] for n in bridge.remote.nodes()]
        return sorted(set(names))

    def get_topic_names_and_types(self) -> list[tuple[str, list[str]]]:
        found: dict[str, set[str]] = {t.name: {t.msg_type.TYPE} for t in self.bus.topics.values()}
        bridge = self._rcl_context.bridge
        if bridge is not None:
            for e in bridge.remote.endpoints():
                if "/msg/" in e.type_name:
                    found.setdefault(e.name, set()).add(e.type_name)
        return sorted((name, sorted(types)) for name, types in found.items())

    def count_publishers(self, topic_name: str) -> int:
        return self._count(topic_name, "MP")

    def count_subscribers(self, topic_name: str) -> int:
        return self._count(topic_name, "MS")

    def _count(self, topic_name: str, kind: str) -> int:
        name = self.resolve_topic_name(topic_name)
        topic = self.bus.topics.get(name)
        local = 0 if topic is None else len(topic.publishers if kind == "MP" else topic.subscriptions)
        bridge = self._rcl_context.bridge
        remote = (
            0
            if bridge is None
            else sum(1 for e in bridge.remote.endpoints() if e.name == name and e.kind == kind)
        )
        return local + remote

    def declare_parameters(self, namespace: str, parameters: list[tuple[str, Any]]) -> list[Parameter]:
        prefix = f"{namespace}." if namespace else ""
        return [self.declare_parameter(prefix + name, value) for name, value, *_ in parameters]


__all__ = ["Node", "Parameter"]
