"""``ros2 topic hz`` for a topic only other processes use: the app subscribes while someone asks.

A topic the app has no endpoint on records no publish times here; the first rate request for it
makes a subscription on a hidden node (``_topic_watch``), which then records every message, and
the subscription goes once nobody has asked for ``IDLE_S``. At most ``MAX_WATCHED`` topics at once.
"""

from __future__ import annotations

from typing import Any

from server.bus import Bus, Node, Subscription
from server.limits import LimitExceededError
from server.msgs import Message

IDLE_S = 30.0
MAX_WATCHED = 16
CHECK_PERIOD_S = 5.0


class TopicWatch(Node):
    def __init__(self, bus: Bus) -> None:
        super().__init__("_topic_watch", context=bus)
        self._subs: dict[str, tuple[Subscription, float]] = {}
        self.create_timer(CHECK_PERIOD_S, self._expire)

    def watch(self, name: str, msg_type: type[Message]) -> None:
        """Keep a subscription on ``name`` for the next ``IDLE_S``."""
        now = self.bus.clock.now()
        held = self._subs.get(name)
        if held is not None:
            self._subs[name] = (held[0], now)
            return
        if len(self._subs) >= MAX_WATCHED:
            raise LimitExceededError("topics watched for their rate", MAX_WATCHED)
        sub = self.create_subscription(msg_type, name, _ignore, 10)
        self._subs[name] = (sub, now)

    def watched(self) -> set[str]:
        return set(self._subs)

    def _expire(self) -> None:
        now = self.bus.clock.now()
        for name, (sub, asked) in list(self._subs.items()):
            if now - asked > IDLE_S:
                self.destroy_subscription(sub)
                del self._subs[name]


def _ignore(_msg: Any) -> None:
    """The rate comes from the topic's own record of publish times; the message is not needed."""
