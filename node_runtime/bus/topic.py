"""A topic on the bus: its publishers and subscriptions, its latest message and the times of its
publishes (for rates), and the delivery of one message to every subscription's queue."""

from __future__ import annotations

from collections import deque
from collections.abc import Callable
from typing import TYPE_CHECKING

from node_runtime.bus.names import is_hidden
from node_runtime.msgs import Message

if TYPE_CHECKING:
    from node_runtime.bus.endpoints import Publisher, Subscription
    from node_runtime.bus.graph import Bus

Tap = Callable[[Message, object], None]

HZ_WINDOW_MAX = 10_000
INTERNAL_TOPICS = frozenset({"/rosout", "/parameter_events"})


class Topic:
    """A named, typed channel; exists while some node publishes or subscribes to it."""

    def __init__(self, bus: Bus, name: str, msg_type: type[Message]) -> None:
        self.bus = bus
        self.name = name
        self.msg_type = msg_type
        self.publishers: list[Publisher] = []
        self.subscriptions: list[Subscription] = []
        self.latest: Message | None = None
        self.latest_time_s: float | None = None
        self.publish_count = 0
        # Publish times for `ros2 topic hz`-style rates, kept always: one deque append per message.
        self.publish_times_s: deque[float] = deque(maxlen=HZ_WINDOW_MAX)
        self.tap: Tap | None = bus.taps.get(name)

    @property
    def hidden(self) -> bool:
        return self.name in INTERNAL_TOPICS or is_hidden(self.name)

    def deliver(
        self,
        msg: Message,
        published_s: float | None = None,
        *,
        handed_over: bool = False,
        source: object = None,
    ) -> int:
        """Queue ``msg`` for every live subscription. ``published_s``: when another process published
        it (its source timestamp), so rates are the publisher's, not this process's arrivals.

        One snapshot of ``msg`` is kept as the topic's latest and given to every read-only
        subscription; any other subscription gets a copy of its own, as a message from another
        process would be. ``handed_over``: ``msg`` is new and nobody will change it (a publisher
        that builds a message for every publish, or one decoded from the wire), so it is the snapshot
        itself; as rclcpp shares one const message among its intra-process subscriptions.
        ``source``: who published it, for the topic's tap (Bus.set_tap)."""
        now = self.bus.clock.now()
        snapshot = msg if handed_over else msg.copy()
        self.latest = snapshot
        self.latest_time_s = now
        self.publish_count += 1
        self.publish_times_s.append(now if published_s is None else published_s)
        if self.tap is not None:
            self.tap(snapshot, source)
        delivered = 0
        ready = self.bus._ready
        for sub in self.subscriptions:
            if sub.destroyed or sub.node._state != "active":  # Subscription.active, inline: the hot path
                continue
            queue = sub.queue
            if len(queue) == sub.depth:
                sub.dropped += 1
            queue.append(snapshot if sub.read_only else snapshot.copy())
            ready.append(sub)
            delivered += 1
        if delivered:
            self.bus._wake()
        return delivered

    def hand_history(self, sub: Subscription) -> None:
        """Queue for ``sub`` (transient local, new) what the topic's transient-local publishers
        kept, as a late joiner gets it in ROS 2."""
        kept = [m for p in self.publishers if p.history and not p.destroyed for m in p.history]
        for msg in kept:
            sub.queue.append(msg if sub.read_only else msg.copy())
            self.bus._ready.append(sub)
        if kept:
            self.bus._wake()
