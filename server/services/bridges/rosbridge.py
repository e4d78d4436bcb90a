"""The rosbridge v2 protocol for one client, as roslibjs 2.x and roslibpy 2.x speak it.

Ops handled: advertise, unadvertise, publish, subscribe (throttle_rate, queue_length),
unsubscribe, call_service (answered by service_response with the request's id), set_level.
Names may come with or without their leading ``/`` and types as ``pkg/Type`` or ``pkg/msg/Type``.

What goes out is bounded: each subscription keeps at most its queue_length messages (the
oldest go first when a client reads slowly), replies and statuses wait in a bounded queue, and
messages are turned into JSON only when they are sent. A client never gets an op it cannot
handle: ``status`` only after it asked for one with ``set_level`` (roslibpy raises on it), and
never a binary frame.
"""

from __future__ import annotations

import asyncio
import itertools
import json
import logging
import math
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from node_runtime.bus import Bus, Node, Publisher, ServiceClient, Subscription, TopicTypeError
from node_runtime.msgs import Message, MessageError, UnknownTypeError, get_type
from server.services.bridges.inbound import check_inbound

log = logging.getLogger("bridges.rosbridge")
_ids = itertools.count(1)

DEFAULT_QUEUE = 100  # queue_length 0 (the clients' default): a slow client still loses only the oldest
# queue_length 0 with a throttle_rate: only the newest message waits for the next send, as
# rosbridge's throttle handler sends nothing older, so a throttled stream is never behind.
THROTTLED_QUEUE = 1
MAX_QUEUE = 1000
MAX_THROTTLE_MS = 60_000
MAX_TOPICS = 256  # subscriptions plus advertisements per client
MAX_PENDING_CALLS = 64
MAX_REPLIES = 1000  # service responses and statuses waiting to be sent
CALL_TIMEOUT_S = 10.0
MAX_CALL_TIMEOUT_S = 300.0
STATUS_LEVELS = {"none": 0, "error": 1, "warning": 2, "info": 3}


class ProtocolError(ValueError):
    """A request that cannot be carried out; reported as a status (when asked for) and logged."""


@dataclass
class Outgoing:
    """One subscription's queue of messages for the client, and its throttle."""

    topic: str  # as the client named it (with or without its leading /)
    ids: set[str]
    throttle_s: float
    queue: deque[Message]
    bus_sub: Subscription
    next_send_s: float = 0.0
    dropped: int = 0


@dataclass
class Stats:
    sent: int = 0
    dropped: int = 0
    refused: int = 0
    ops: dict[str, int] = field(default_factory=dict)


def _absolute(name: Any, what: str) -> str:
    if not isinstance(name, str) or not name.strip("/"):
        raise ProtocolError(f"{what} must be a non-empty name, got {name!r}")
    return name if name.startswith("/") else "/" + name


def _int(value: Any, what: str, low: int, high: int, default: int) -> int:
    if value is None:
        return default
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ProtocolError(f"{what} must be a number, got {value!r}")
    return min(max(int(value), low), high)


def _json_safe(value: Any) -> Any:
    """NaN and infinities as null: JSON has no words for them and JSON.parse would reject the frame."""
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {k: _json_safe(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_json_safe(v) for v in value]
    return value


def encode(frame: dict[str, Any]) -> str:
    try:
        return json.dumps(frame, allow_nan=False, separators=(",", ":"))
    except ValueError:
        return json.dumps(_json_safe(frame), allow_nan=False, separators=(",", ":"))


class RosbridgeSession:
    """One connected client: its hidden node on the bus and its bounded outgoing queues."""

    def __init__(
        self,
        bus: Bus,
        loop: asyncio.AbstractEventLoop | None = None,
        limits_name: Callable[[str], str] | None = None,
    ) -> None:
        """``limits_name``: the name whose limits (node_runtime/limits.py) a topic's messages keep; a class
        server's ``/ada/uav/input/position`` keeps those of the world's ``/uav/input/position``."""
        self.limits_name = limits_name or (lambda topic: topic)
        with bus.activate():
            self.node = Node(f"_rosbridge_{next(_ids)}")
        self.loop = loop or asyncio.get_running_loop()
        self.subscriptions: dict[str, Outgoing] = {}
        self.advertised: dict[str, Publisher] = {}
        self.clients: dict[str, ServiceClient] = {}
        self.pending_calls = 0
        self.replies: deque[str] = deque(maxlen=MAX_REPLIES)
        self.status_level = STATUS_LEVELS["none"]
        self.stats = Stats()
        self.ready = asyncio.Event()
        self._rotation = 0
        self._call_timers: set[asyncio.TimerHandle] = set()

    # -- incoming --------------------------------------------------------
    def handle(self, request: dict[str, Any]) -> None:
        """Carry out one request (a decoded JSON object); a bad one is reported, never raised."""
        op = request.get("op")
        self.stats.ops[str(op)] = self.stats.ops.get(str(op), 0) + 1
        handler = _HANDLERS.get(op) if isinstance(op, str) else None
        try:
            if handler is None:
                raise ProtocolError(f"op {op!r} is not supported by this server")
            handler(self, request)
        except (ProtocolError, MessageError, UnknownTypeError, TopicTypeError, ValueError) as exc:
            self.stats.refused += 1
            log.info("rosbridge client %s: %s: %s", self.node.get_name(), op, exc)
            self.status("error", f"{op}: {exc}", request.get("id"))

    def _advertise(self, request: dict[str, Any]) -> None:
        topic = _absolute(request.get("topic"), "topic")
        msg_type = get_type(str(request.get("type", "")))
        pub = self.advertised.get(topic)
        if pub is not None and pub.msg_type is msg_type:
            return
        self._check_room(topic)
        if pub is not None:
            self.node.destroy_publisher(pub)
        self.advertised[topic] = self.node.create_publisher(msg_type, topic, 10)

    def _unadvertise(self, request: dict[str, Any]) -> None:
        pub = self.advertised.pop(_absolute(request.get("topic"), "topic"), None)
        if pub is not None:
            self.node.destroy_publisher(pub)

    def _publish(self, request: dict[str, Any]) -> None:
        topic = _absolute(request.get("topic"), "topic")
        pub = self.advertised.get(topic)
        if pub is None:  # rosbridge lets a client publish on an existing topic without advertising it
            existing = self.node.bus.topic_type(topic)  # here or in another process
            if existing is None:
                raise ProtocolError(
                    f"{topic} is not advertised and does not exist: advertise it with its type"
                )
            self._check_room(topic)
            pub = self.advertised[topic] = self.node.create_publisher(existing, topic, 10)
        as_json = request.get("msg", {})
        message = pub.msg_type.from_dict(as_json)
        check_inbound(self.limits_name(topic), message, as_json)
        pub.publish(message)

    def _subscribe(self, request: dict[str, Any]) -> None:
        topic = _absolute(request.get("topic"), "topic")
        as_named = str(request["topic"])  # frames go out under the client's spelling: it dispatches on it
        sub_id = str(request.get("id", ""))
        throttle_s = _int(request.get("throttle_rate"), "throttle_rate", 0, MAX_THROTTLE_MS, 0) / 1000.0
        depth = _int(request.get("queue_length"), "queue_length", 0, MAX_QUEUE, 0) or (
            THROTTLED_QUEUE if throttle_s else DEFAULT_QUEUE
        )
        existing = self.node.bus.topic_type(topic)  # here or in another process
        if request.get("type"):
            msg_type = get_type(str(request["type"]))
            if existing is not None and existing is not msg_type:
                raise TopicTypeError(f"{topic} carries {existing.TYPE}, not {msg_type.TYPE}")
        elif existing is not None:
            msg_type = existing
        else:
            raise ProtocolError(f"{topic} does not exist yet: subscribe with its type")
        out = self.subscriptions.get(as_named)
        if out is not None:  # one stream per topic, as rosbridge merges a client's subscriptions
            out.ids.add(sub_id)
            out.throttle_s = min(out.throttle_s, throttle_s)
            if depth > (out.queue.maxlen or 0):
                out.queue = deque(out.queue, maxlen=depth)
            return
        self._check_room(as_named)
        queue: deque[Message] = deque(maxlen=depth)
        bus_sub = self.node.create_subscription(msg_type, topic, self._on_message(as_named), depth)
        self.subscriptions[as_named] = Outgoing(as_named, {sub_id}, throttle_s, queue, bus_sub)

    def _unsubscribe(self, request: dict[str, Any]) -> None:
        _absolute(request.get("topic"), "topic")
        topic = str(request["topic"])
        out = self.subscriptions.get(topic)
        if out is None:
            return
        if request.get("id") is not None:
            out.ids.discard(str(request["id"]))
            if out.ids:
                return
        del self.subscriptions[topic]
        self.node.destroy_subscription(out.bus_sub)

    def _call_service(self, request: dict[str, Any]) -> None:
        name = _absolute(request.get("service"), "service")
        as_named = str(request["service"])
        call_id = request.get("id")
        channel = self.node.bus.services.get(name)
        if channel is None or not any(s.active for s in channel.servers):
            self._reply_call(as_named, call_id, f"Service {name} does not exist", ok=False)
            return
        if self.pending_calls >= MAX_PENDING_CALLS:
            self._reply_call(as_named, call_id, f"{MAX_PENDING_CALLS} calls already pending", ok=False)
            return
        client = self.clients.get(name)
        if client is None or client.srv_type is not channel.srv_type:
            client = self.clients[name] = self.node.create_client(channel.srv_type, name)
        args = request.get("args") or {}
        if isinstance(args, list):  # rosbridge also takes the request's fields in order
            args = dict(zip((f.name for f in client.srv_type.Request.FIELDS), args, strict=False))
        future = client.call_async(client.srv_type.Request.from_dict(args))
        self.pending_calls += 1
        timeout_s = (
            float(_int(request.get("timeout"), "timeout", 0, int(MAX_CALL_TIMEOUT_S), 0)) or CALL_TIMEOUT_S
        )
        answered = False

        def done(_future: Any) -> None:
            nonlocal answered
            if answered:
                return
            answered = True
            self.pending_calls -= 1
            timer.cancel()
            self._call_timers.discard(timer)
            if future.done() and future.exception() is None and future.result() is not None:
                self._reply_call(as_named, call_id, future.result().to_dict(), ok=True)  # type: ignore[union-attr]
            else:
                why = future.exception() or f"no answer within {timeout_s:g} s"
                self._reply_call(as_named, call_id, str(why), ok=False)

        timer = self.loop.call_later(timeout_s, done, None)
        self._call_timers.add(timer)
        future.add_done_callback(done)

    def _set_level(self, request: dict[str, Any]) -> None:
        level = request.get("level")
        if level not in STATUS_LEVELS:
            raise ProtocolError(f"level must be one of {', '.join(STATUS_LEVELS)}, got {level!r}")
        self.status_level = STATUS_LEVELS[level]

    def _check_room(self, topic: str) -> None:
        new = topic not in self.subscriptions and topic not in self.advertised
        if new and len(self.subscriptions) + len(self.advertised) >= MAX_TOPICS:
            raise ProtocolError(f"a client may use at most {MAX_TOPICS} topics")

    # -- outgoing --------------------------------------------------------
    def _on_message(self, topic: str) -> Any:
        def enqueue(msg: Message) -> None:
            out = self.subscriptions.get(topic)
            if out is None:
                return
            if len(out.queue) == out.queue.maxlen:
                out.dropped += 1
                self.stats.dropped += 1
            out.queue.append(msg)
            self.ready.set()

        return enqueue

    def _reply_call(self, service: str, call_id: Any, values: Any, *, ok: bool) -> None:
        frame: dict[str, Any] = {"op": "service_response", "service": service, "values": values, "result": ok}
        if call_id is not None:
            frame["id"] = call_id
        self._reply(encode(frame))

    def status(self, level: str, text: str, request_id: Any = None) -> None:
        """A status op, only to a client that asked for this level with set_level."""
        if self.status_level < STATUS_LEVELS[level]:
            return
        frame: dict[str, Any] = {"op": "status", "level": level, "msg": text}
        if request_id is not None:
            frame["id"] = request_id
        self._reply(encode(frame))

    def _reply(self, text: str) -> None:
        if len(self.replies) == self.replies.maxlen:
            self.stats.dropped += 1
        self.replies.append(text)
        self.ready.set()

    def next_frame(self, now_s: float) -> tuple[str | None, float | None]:
        """The next frame to send and None, or None and how long until a throttled one is due
        (None: nothing is waiting at all)."""
        if self.replies:
            return self.replies.popleft(), None
        outs = list(self.subscriptions.values())
        wait: float | None = None
        for i in range(len(outs)):  # round robin, so one busy topic cannot starve the others
            out = outs[(self._rotation + i) % len(outs)]
            if not out.queue:
                continue
            if now_s < out.next_send_s:
                wait = min(wait, out.next_send_s - now_s) if wait is not None else out.next_send_s - now_s
                continue
            self._rotation = (self._rotation + i + 1) % len(outs)
            msg = out.queue.popleft()
            out.next_send_s = now_s + out.throttle_s
            self.stats.sent += 1
            return encode({"op": "publish", "topic": out.topic, "msg": msg.to_dict()}), None
        return None, wait

    def close(self) -> None:
        for timer in self._call_timers:
            timer.cancel()
        self._call_timers.clear()
        self.node.destroy_node()
        self.subscriptions.clear()
        self.advertised.clear()
        self.clients.clear()


_HANDLERS: dict[str, Any] = {
    "advertise": RosbridgeSession._advertise,
    "unadvertise": RosbridgeSession._unadvertise,
    "publish": RosbridgeSession._publish,
    "subscribe": RosbridgeSession._subscribe,
    "unsubscribe": RosbridgeSession._unsubscribe,
    "call_service": RosbridgeSession._call_service,
    "set_level": RosbridgeSession._set_level,
}
