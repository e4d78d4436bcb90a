"""WebSocket echo: ``/ws/topics/{name}`` streams a topic live, like ``ros2 topic echo``.

The subscription's callback only appends to a bounded deque; a separate task sends. A slow
client loses the oldest messages (counted in ``dropped``), it never holds up the bus.
"""

from __future__ import annotations

import asyncio
import itertools
from collections import deque
from typing import Any

from fastapi import APIRouter, Query, WebSocket, WebSocketDisconnect

from server.bus import Node, validate_topic_name
from server.msgs import Message, get_type

from .deps import WsLabDep
from .errors import CloseCode, close_code

router = APIRouter(tags=["websockets"])
_ids = itertools.count(1)
MAX_QUEUE = 1000


class EchoNode(Node):
    """Hidden node ``_ws_echo_N``: one per WebSocket client, as ros2 topic echo makes one."""

    def __init__(self, topic: str, msg_type: type[Message], queue_length: int) -> None:
        super().__init__(f"_ws_echo_{next(_ids)}")
        self.outbox: deque[tuple[Message, float]] = deque(maxlen=queue_length)
        self.dropped = 0
        self.ready = asyncio.Event()
        self.sub = self.create_subscription(msg_type, topic, self.on_message, queue_length)

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
        raise ValueError(f"{name} must be an integer, got {text!r}") from None
    if not low <= value <= high:
        raise ValueError(f"{name} must be in {low}..{high}, got {value}")
    return value


@router.websocket("/ws/topics/{name:path}")
async def echo(
    websocket: WebSocket,
    name: str,
    lab: WsLabDep,
    throttle_rate: str | None = Query(
        None, description="minimum ms between frames, 0..60000 (rosbridge's name)"
    ),
    queue_length: str | None = Query(
        None, description=f"messages kept for a slow client, 1..{MAX_QUEUE} (100)"
    ),
    type: str | None = Query(None, description="message type, to echo a topic that does not exist yet"),
) -> None:
    await websocket.accept()
    try:
        throttle_ms = _int_param("throttle_rate", throttle_rate, 0, 0, 60_000)
        depth = _int_param("queue_length", queue_length, 100, 1, MAX_QUEUE)
        topic = "/" + validate_topic_name(name).lstrip("/")
        existing = lab.bus.topics.get(topic)
        if existing is None and type is None:
            await websocket.close(
                CloseCode.UNKNOWN_TOPIC, f"unknown topic {topic}; pass ?type= to wait for it"
            )
            return
        msg_type = existing.msg_type if type is None else get_type(type)
        with lab.bus.activate():
            node = EchoNode(topic, msg_type, depth)
    except Exception as exc:
        await websocket.close(close_code(exc), str(exc)[:120])
        return
    sender = asyncio.create_task(_send_loop(websocket, node, topic, throttle_ms / 1000.0))
    try:
        await _receive_until_closed(websocket, lab.settings.max_ws_frame_bytes)
    finally:
        sender.cancel()
        node.destroy_node()


async def _send_loop(websocket: WebSocket, node: EchoNode, topic: str, throttle_s: float) -> None:
    type_name = node.sub.msg_type.TYPE
    try:
        while True:
            await node.ready.wait()
            node.ready.clear()
            while node.outbox:
                msg, received = node.outbox.popleft()
                frame: dict[str, Any] = {
                    "topic": topic,
                    "type": type_name,
                    "msg": msg.to_dict(),
                    "received": received,
                }
                if node.dropped:
                    frame["dropped"] = node.dropped
                await websocket.send_json(frame)
                if throttle_s:
                    await asyncio.sleep(throttle_s)
    except (WebSocketDisconnect, RuntimeError, asyncio.CancelledError):
        return


async def _receive_until_closed(websocket: WebSocket, max_frame_bytes: int) -> None:
    """The echo channel only sends; anything a client sends is refused with a named close code."""
    try:
        while True:
            frame = await websocket.receive()
            if frame["type"] == "websocket.disconnect":
                return
            data = frame.get("text") or frame.get("bytes") or b""
            if len(data) > max_frame_bytes:
                await websocket.close(CloseCode.MESSAGE_TOO_BIG, f"frame larger than {max_frame_bytes} bytes")
            else:
                await websocket.close(CloseCode.UNSUPPORTED_DATA, "the echo channel takes no messages")
            return
    except (WebSocketDisconnect, RuntimeError):
        return
