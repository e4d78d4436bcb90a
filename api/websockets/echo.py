"""WebSocket echo: ``/ws/topics/{name}`` streams a topic live, like ``ros2 topic echo``.

The subscription's callback only appends to a bounded deque; a separate task sends. A slow
client loses the oldest messages (counted in ``dropped``), it never holds up the bus.

Everything a request asks is checked before its node exists, and the node, its subscription
and its sender task go when the socket goes, however it ends. Node names are recycled (the
lowest free number), so churn does not leave a logger per connection behind either.
"""

from __future__ import annotations

import asyncio
from collections import deque

from fastapi import APIRouter, Query, WebSocket, WebSocketDisconnect

from api.deps import WsLabDep
from api.errors import CloseCode, close_code, close_reason
from api.protocol.frames import EchoFrame
from api.protocol.json_codec import dumps
from api.websockets.budget import spend
from api.websockets.life import closed_when_lab_stops
from api.websockets.send_only import refuse_client_frames
from node_runtime.bus import Bus, Node, UnknownTopicError, validate_topic_name
from node_runtime.limits import LimitExceededError, RateLimit
from node_runtime.msgs import Message
from node_runtime.transport.keys import TRANSIENT_LOCAL, VOLATILE, EntityKind, QoS
from server.world.lab import Lab

router = APIRouter(tags=["websockets"])
MAX_QUEUE = 1000
NODE_PREFIX = "_ws_echo_"


class EchoRequestError(ValueError):
    """A query value the echo channel cannot take (closed with 4400 and this text)."""


class EchoNode(Node):
    """Hidden node ``_ws_echo_N``: one per WebSocket client, as ros2 topic echo makes one."""

    def __init__(
        self, number: int, topic: str, msg_type: type[Message], queue_length: int, bus: Bus, durability: int
    ) -> None:
        super().__init__(f"{NODE_PREFIX}{number}", context=bus)
        self.number = number
        self.outbox: deque[tuple[Message, float]] = deque(maxlen=queue_length)
        self.dropped = 0
        self.ready = asyncio.Event()
        qos = QoS(depth=queue_length, durability=durability)
        # Read only: a message is turned into JSON and never changed, so the topic's one snapshot serves.
        self.sub = self.create_subscription(msg_type, topic, self.on_message, qos, read_only=True)

    def on_message(self, msg: Message) -> None:
        if len(self.outbox) == self.outbox.maxlen:
            self.dropped += 1
        self.outbox.append((msg, self.bus.clock.now()))
        self.ready.set()


def _int_param(name: str, text: str | None, default: int, low: int, high: int) -> int:
    """A query value checked here, after the handshake, so a browser sees the reason too."""
    if text is None:
        return default
    try:
        value = int(text)
    except ValueError:
        raise EchoRequestError(f"{name} must be an integer, got {text[:20]!r}") from None
    if not low <= value <= high:
        raise EchoRequestError(f"{name} must be in {low}..{high}, got {value}")
    return value


def offered_durability(lab: Lab, topic: str) -> int:
    """Transient local when every publisher on ``topic`` offers it, else volatile: ros2 topic echo
    adapts its QoS so, and so prints what a transient-local publisher (``/tf_static``) sent
    before the echo began."""
    local = lab.bus.topics.get(topic)
    offered = [getattr(p.qos, "durability", 0) for p in (local.publishers if local is not None else [])]
    remote = lab.remote_graph()
    if remote is not None:
        offered += [e.qos.durability for e in remote.endpoints([EntityKind.PUBLISHER]) if e.name == topic]
    return TRANSIENT_LOCAL if offered and all(d == TRANSIENT_LOCAL for d in offered) else VOLATILE


def _echo_nodes(bus: Bus) -> list[EchoNode]:
    return [n for n in bus.nodes if isinstance(n, EchoNode)]


def open_echo(lab: Lab, name: str, type_name: str | None, depth: int) -> EchoNode:
    """Check the request against the bus and the app's limit, then make the node (or nothing)."""
    topic = "/" + validate_topic_name(name).lstrip("/")
    msg_type = lab.topic_type(topic, type_name)
    taken = {n.number for n in _echo_nodes(lab.bus)}
    if len(taken) >= lab.settings.limits.max_echo_sockets:
        raise LimitExceededError("echo sockets", lab.settings.limits.max_echo_sockets)
    number = next(i for i in range(1, len(taken) + 2) if i not in taken)
    return EchoNode(number, topic, msg_type, depth, lab.bus, offered_durability(lab, topic))


def _refusal(exc: Exception, topic: str) -> tuple[int, str]:
    if isinstance(exc, EchoRequestError):
        return CloseCode.BAD_REQUEST, str(exc)
    if isinstance(exc, UnknownTopicError):
        return CloseCode.NOT_FOUND, f"unknown topic {topic}; pass ?type= to wait for it"
    code = close_code(exc)
    if code is None:
        raise exc  # a bug: ErrorMiddleware closes with 1011 and logs it
    return code, str(exc)


@router.websocket("/ws/topics/{name:path}")
async def echo(
    websocket: WebSocket,
    name: str,
    lab: WsLabDep,
    throttle_rate: str | None = Query(
        None, description="minimum ms between frames, 0..60000 (rosbridge's name)"
    ),
    queue_length: str | None = Query(
        None, description=f"messages kept for a slow client, 1..{MAX_QUEUE} (100; 1 with throttle_rate)"
    ),
    type: str | None = Query(None, description="message type, to echo a topic that does not exist yet"),
) -> None:
    await websocket.accept()
    try:
        throttle_ms = _int_param("throttle_rate", throttle_rate, 0, 0, 60_000)
        # A throttled stream keeps only the newest message unless asked for more: a queue of 100
        # behind a 30 Hz throttle on a 100 Hz topic would send messages 3 s old.
        depth = _int_param("queue_length", queue_length, 1 if throttle_ms else 100, 1, MAX_QUEUE)
        node = open_echo(lab, name, type, depth)
    except Exception as exc:
        code, reason = _refusal(exc, "/" + name.lstrip("/"))
        await websocket.close(code, close_reason(reason))
        return
    sender = asyncio.create_task(_send_loop(websocket, node, throttle_ms / 1000.0, lab.socket_frames))
    try:
        async with closed_when_lab_stops(websocket, lab):
            await refuse_client_frames(websocket, lab.settings.listen.max_ws_frame_bytes, "echo")
    finally:
        sender.cancel()
        node.destroy_node()
        await asyncio.gather(sender, return_exceptions=True)


async def _send_loop(
    websocket: WebSocket, node: EchoNode, throttle_s: float, frames: RateLimit | None
) -> None:
    topic, type_name = node.sub.topic_name, node.sub.msg_type.TYPE
    try:
        while True:
            await node.ready.wait()
            node.ready.clear()
            while node.outbox:
                await spend(frames)  # the lab's budget: over it this echo waits, its oldest messages drop
                msg, received = node.outbox.popleft()
                frame: EchoFrame = {
                    "topic": topic,
                    "type": type_name,
                    "msg": msg.to_dict(),
                    "received": received,
                }
                if node.dropped:
                    frame["dropped"] = node.dropped
                await websocket.send_text(dumps(frame))
                if throttle_s:
                    await asyncio.sleep(throttle_s)
    except (WebSocketDisconnect, RuntimeError, asyncio.CancelledError):
        return
