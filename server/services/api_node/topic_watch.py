"""A topic only other processes use, seen from the app's tools: the app listens while someone asks.

The app records a topic's latest message and publish times only for what reaches its bus. A
topic that another process publishes and nothing in the app subscribes to never reaches it, so
the first request for its latest message or its rate (``GET /api/topics/{name}``, ``GET
/api/hz/{name}``) makes a subscription on a hidden node (``_topic_watch``), as ``ros2 topic echo``
makes one, and says so (``started``); the topic then records every message, and the subscription
goes once nobody has asked for ``IDLE_S``. The echo WebSocket, bag record and the bridges
subscribe by themselves, so they need no watch. At most ``MAX_WATCHED`` topics at once.
"""

from __future__ import annotations

from typing import Any, Literal

from node_runtime.bus import Bus, Node, Subscription
from node_runtime.limits import LimitExceededError
from node_runtime.msgs import Message

IDLE_S = 30.0
MAX_WATCHED = 16
CHECK_PERIOD_S = 5.0
NODE_NAME = "_topic_watch"

WatchState = Literal["started", "running"]
"""``started``: this request began listening (messages show from now on); ``running``: an earlier
request's listening goes on."""


class TopicWatch(Node):
    def __init__(self, bus: Bus) -> None:
        super().__init__(NODE_NAME, context=bus)
        self._subs: dict[str, tuple[Subscription, float]] = {}
        self.create_timer(CHECK_PERIOD_S, self._expire)

    def needed(self, name: str) -> bool:
        """Whether the app needs a watch to see ``name``'s messages: nothing of its own subscribes,
        and the topic is not the app's alone (on a topic it only publishes on, another process's
        messages would not come; its own it records as it publishes them)."""
        if name in self._subs:
            return True
        topic = self.bus.topics.get(name)
        if topic is None:
            return True
        if any(not s.destroyed for s in topic.subscriptions):
            return False
        remote = self.bus.remote_topics
        return remote is not None and name in remote.topic_types()

    def has_room(self, name: str) -> bool:
        return name in self._subs or len(self._subs) < MAX_WATCHED

    def watch(self, name: str, msg_type: type[Message]) -> WatchState:
        """Keep a subscription on ``name`` for the next ``IDLE_S``; LimitExceededError when
        ``MAX_WATCHED`` other topics are watched already."""
        now = self.bus.clock.now()
        held = self._subs.get(name)
        if held is not None:
            self._subs[name] = (held[0], now)
            return "running"
        if len(self._subs) >= MAX_WATCHED:
            raise LimitExceededError("topics the app listens to for the tools", MAX_WATCHED)
        sub = self.create_subscription(msg_type, name, _ignore, 10)
        self._subs[name] = (sub, now)
        return "started"

    def watched(self) -> set[str]:
        return set(self._subs)

    def _expire(self) -> None:
        now = self.bus.clock.now()
        for name, (sub, asked) in list(self._subs.items()):
            if now - asked > IDLE_S:
                self.destroy_subscription(sub)
                del self._subs[name]


def _ignore(_msg: Any) -> None:
    """The topic itself keeps the latest message and the publish times; the callback needs nothing."""
