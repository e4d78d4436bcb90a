"""``ros2 bag record``: a node that subscribes to topics and writes what it hears into a bag.

With ``all_topics`` it records every topic but the hidden ones (``_``-prefixed parts), including
topics that appear after it started, as ``ros2 bag record -a`` does; it looks for new ones
each ``discovery_period_s``.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from node_runtime.bus import Node, RosTime, is_hidden
from node_runtime.msgs import Message
from node_runtime.msgs.wire import serialize
from server.peripherals.bag.writer import BagMessage, BagWriter

DISCOVERY_PERIOD_S = 0.5
SUBSCRIPTION_DEPTH = 1000  # rosbag2 subscribes with a deep queue: a burst must not be lost


class RecorderNode(Node):
    """Node ``rosbag2_recorder`` (as ros2 bag names its own); feeds a BagWriter."""

    def __init__(
        self,
        writer: BagWriter,
        topics: Iterable[str] = (),
        *,
        all_topics: bool = False,
        max_bytes: int | None = None,
        node_name: str = "rosbag2_recorder",
    ) -> None:
        super().__init__(node_name)
        self.writer = writer
        self.all_topics = all_topics
        self.max_bytes = max_bytes
        self.full = False
        self.wanted = {self.resolve_topic_name(t) for t in topics}
        self._graph_version: tuple[int, int] | None = None
        self._recorded: set[str] = set()
        self._discover()
        if all_topics or self.wanted - self._recorded:
            self.create_timer(DISCOVERY_PERIOD_S, self._discover)

    @property
    def recorded_topics(self) -> list[str]:
        return sorted(self._recorded)

    def flush(self) -> None:
        """Record what was delivered but not yet handled, so stopping loses nothing already heard."""
        for sub in self.subscriptions:
            while sub.active and sub.queue:
                sub.callback(sub.queue.popleft())

    def _discover(self) -> None:
        """Subscribe to the topics that exist now and are wanted (all, with -a)."""
        version = self.bus.topics_version
        if version == self._graph_version:
            return
        self._graph_version = version
        # Other processes' topics too (a student's node process), as ros2 bag records the graph's.
        for name, msg_type in self.bus.known_topics().items():
            if name in self._recorded or (is_hidden(name) if self.all_topics else name not in self.wanted):
                continue
            self._recorded.add(name)
            self.create_subscription(msg_type, name, self._writer_for(name), SUBSCRIPTION_DEPTH)

    def _writer_for(self, topic: str) -> Any:
        def record(msg: Message) -> None:
            if self.full:
                return
            stamp = RosTime.from_seconds(self.bus.clock.now()).nanoseconds
            self.writer.submit(BagMessage(topic, msg.TYPE, stamp, serialize(msg)))
            if self.max_bytes is not None and self.writer.stats.bytes_written > self.max_bytes:
                self.full = True
                self.get_logger().warning(f"bag reached {self.max_bytes} bytes; recording stopped")

        return record
