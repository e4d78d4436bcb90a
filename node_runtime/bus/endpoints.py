"""Publishers, subscriptions and timers: what a node creates on the bus."""

from __future__ import annotations

from collections import deque
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, Protocol

from node_runtime.bus.errors import DestroyedError, InvalidQoSError, TopicTypeError
from node_runtime.msgs import Message

if TYPE_CHECKING:
    from node_runtime.bus.node import Node
    from node_runtime.bus.topic import Topic

MAX_DEPTH = 10_000


def qos_depth(qos: Any) -> int:
    """A queue depth from an int or a QoS-profile-like object with ``depth``."""
    depth = getattr(qos, "depth", qos)
    if isinstance(depth, bool) or not isinstance(depth, int):
        raise InvalidQoSError(f"queue depth must be an integer, got {depth!r}")
    if not 1 <= depth <= MAX_DEPTH:
        raise InvalidQoSError(f"queue depth must be in 1..{MAX_DEPTH}, got {depth}")
    return depth


TRANSIENT_LOCAL = 1  # rmw's durability value (a profile's, or the bus's WireQoS)


def transient_local(qos: Any) -> bool:
    """Whether a profile (or a bare depth, never) asks for transient-local durability."""
    return getattr(qos, "durability", 0) == TRANSIENT_LOCAL


class RemoteOut(Protocol):
    """Where a publisher's messages also go when another process subscribes (the transport)."""

    def put(self, msg: Message) -> None: ...


class Publisher:
    """Sends messages of one type on one topic; ``publish`` never runs a callback itself."""

    def __init__(
        self, node: Node, topic: Topic, msg_type: type[Message], depth: int, *, hand_over: bool = False
    ) -> None:
        self.node = node
        self.topic = topic
        self.msg_type = msg_type
        self.depth = depth
        self.hand_over = hand_over  # every message published is new and never changed after: no copy
        self.destroyed = False
        self.remote: RemoteOut | None = None
        self.qos: Any = None  # the QoS profile it was made with, when not a bare depth (for the wire)
        # A transient-local publisher's last ``depth`` messages, for subscriptions that come later.
        self.history: deque[Message] | None = None

    @property
    def topic_name(self) -> str:
        return self.topic.name

    def publish(self, msg: Message) -> int:
        """Queue ``msg`` for every live subscription; returns how many it reached."""
        if self.destroyed:
            raise DestroyedError(f"publisher on {self.topic.name} was destroyed")
        if type(msg) is not self.msg_type:
            raise TopicTypeError(
                f"{self.topic.name} carries {self.msg_type.TYPE}; cannot publish {type(msg).__name__}"
                f" ({getattr(msg, 'TYPE', type(msg).__name__)})"
            )
        lock = self.topic.bus.lock
        if lock is None:
            reached = self._deliver(msg)
        else:
            with lock:
                reached = self._deliver(msg)
        if self.remote is not None:
            self.remote.put(msg)
        return reached

    def _deliver(self, msg: Message) -> int:
        reached = self.topic.deliver(msg, handed_over=self.hand_over, source=self)
        if self.history is not None and self.topic.latest is not None:
            self.history.append(self.topic.latest)  # the snapshot deliver made: nobody changes it
        return reached

    def get_subscription_count(self) -> int:
        return sum(1 for s in self.topic.subscriptions if s.active)

    def destroy(self) -> None:
        self.node.destroy_publisher(self)


class Subscription:
    """Receives a topic's messages into a keep-last queue of ``depth``; the executor runs the callback."""

    def __init__(
        self,
        node: Node,
        topic: Topic,
        msg_type: type[Message],
        callback: Callable[[Any], Any],
        depth: int,
        *,
        read_only: bool = False,
    ) -> None:
        if topic.msg_type is not msg_type:
            raise TopicTypeError(f"{topic.name} carries {topic.msg_type.TYPE}, not {msg_type.TYPE}")
        self.node = node
        self.topic = topic
        self.msg_type = msg_type
        self.callback = callback
        self.depth = depth
        self.read_only = read_only  # the callback never changes a message: it gets the shared one
        self.qos: Any = None  # the QoS profile it was made with, when not a bare depth (for the wire)
        self.queue: deque[Message] = deque(maxlen=depth)
        self.dropped = 0
        self.destroyed = False

    @property
    def topic_name(self) -> str:
        return self.topic.name

    @property
    def active(self) -> bool:
        return not self.destroyed and self.node._state == "active"

    def destroy(self) -> None:
        self.node.destroy_subscription(self)


class Timer:
    """Calls ``callback`` every ``period_s`` on the bus clock, keeping phase (missed calls are skipped)."""

    LATENESS_SAMPLES = 2000

    def __init__(self, node: Node, period_s: float, callback: Callable[[], Any], start_s: float) -> None:
        if not (isinstance(period_s, (int, float)) and 0 < period_s < 1e7):
            raise ValueError(f"timer period must be a positive number of seconds, got {period_s!r}")
        self.node = node
        self.period_s = float(period_s)
        self.callback = callback
        self._start_s = start_s
        self._n = 1
        # When the next call is due: kept as a plain attribute, read on every executor pass.
        self.next_deadline_s = start_s + self.period_s
        self.cancelled = False
        self.call_count = 0
        self.lateness_s: deque[float] = deque(maxlen=self.LATENESS_SAMPLES)

    def advance_past(self, now_s: float) -> None:
        self.lateness_s.append(now_s - self.next_deadline_s)
        start, period = self._start_s, self.period_s
        n = max(self._n + 1, int((now_s - start) / period) + 1)
        while start + n * period <= now_s:
            n += 1
        bus = self.node._bus
        bus.timer_calls += 1
        if n > self._n + 1:  # the calls due between this one and the next were skipped
            bus.timer_calls_skipped += n - self._n - 1
        self._n = n
        self.next_deadline_s = start + n * period

    def cancel(self) -> None:
        self.cancelled = True

    def is_canceled(self) -> bool:
        return self.cancelled

    def reset(self) -> None:
        """Restart the period from now, as rclpy's ``Timer.reset``."""
        self.cancelled = False
        self._start_s = self.node._bus.clock.now()
        self._n = 1
        self.next_deadline_s = self._start_s + self.period_s
        self.node._bus.schedule(self)

    def destroy(self) -> None:
        self.node.destroy_timer(self)
