"""A probe node that records topics as rqt would (the bus and clock fixtures are in tests/conftest.py)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pytest

from node_runtime.bus import Bus, Node
from node_runtime.msgs import Log, Message


class Recorder:
    """Subscribes a probe node to topics and keeps ``(time_s, msg)`` for each one received."""

    def __init__(self, bus: Bus, topics: dict[str, type[Message]], name: str = "probe") -> None:
        self.node = Node(name, context=bus)
        self.got: dict[str, list[tuple[float, Any]]] = {}
        for topic, msg_type in topics.items():
            self.got[topic] = []
            self.node.create_subscription(msg_type, topic, self._recorder(topic), 10_000)

    def _recorder(self, topic: str) -> Callable[[Message], None]:
        def record(msg: Message) -> None:
            self.got[topic].append((self.node.bus.clock.now(), msg))

        return record

    def data(self, topic: str, after_s: float = -1.0) -> list[Any]:
        return [m.data for t, m in self.got[topic] if t > after_s]

    def times(self, topic: str) -> list[float]:
        return [t for t, _ in self.got[topic]]

    def logs(self, node_name: str) -> list[str]:
        return [m.msg for _, m in self.got["/rosout"] if m.name == node_name]

    def log_times(self, node_name: str, text: str) -> list[float]:
        return [t for t, m in self.got["/rosout"] if m.name == node_name and text in m.msg]


@pytest.fixture
def record(bus: Bus) -> Callable[[dict[str, type[Message]]], Recorder]:
    """``record({topic: type})``: make the probe before the nodes under test, to see their first logs."""

    def make(topics: dict[str, type[Message]]) -> Recorder:
        return Recorder(bus, {"/rosout": Log, **topics})

    return make
