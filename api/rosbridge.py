"""WebSocket: the rosbridge v2 endpoint at ``/rosbridge`` (roslibjs, roslibpy), behind the app's guard.

The protocol is server/bridges/rosbridge.py; here are its transport and its limits. Frames are
JSON text; a binary frame, a frame that is not a JSON object, or one over the size limit closes
the connection with a close code that says which. A task of its own sends, so a client that
reads slowly only loses the oldest messages of its subscriptions.
"""

from __future__ import annotations

import asyncio
import contextlib
import json

from fastapi import APIRouter, WebSocket, WebSocketDisconnect

from server.bridges.rosbridge import RosbridgeSession
from server.tasks import cancel_and_wait

from .deps import WsLabDep
from .errors import CloseCode
from .ws_life import closed_when_lab_stops

router = APIRouter(tags=["websockets"])
MAX_FRAME_BYTES = 1 << 20  # a publish of the largest message any lab type can hold fits


@router.websocket("/rosbridge")
async def rosbridge(websocket: WebSocket, lab: WsLabDep) -> None:
    await websocket.accept()
    session = RosbridgeSession(lab.bus)
    sender = asyncio.create_task(_send_loop(websocket, session))
    try:
        async with closed_when_lab_stops(websocket, lab):
            close = await _receive_loop(websocket, session)
    finally:
        await cancel_and_wait(sender)
        session.close()
    if close is not None:
        with contextlib.suppress(RuntimeError, WebSocketDisconnect):
            await websocket.close(*close)


async def _receive_loop(websocket: WebSocket, session: RosbridgeSession) -> tuple[int, str] | None:
    """Handle requests until the client leaves (None) or must be closed (code, reason)."""
    try:
        while (frame := await websocket.receive())["type"] != "websocket.disconnect":
            text = frame.get("text")
            if text is None:
                return CloseCode.UNSUPPORTED_DATA, "rosbridge frames are JSON text"
            if len(text) > MAX_FRAME_BYTES:
                return CloseCode.MESSAGE_TOO_BIG, f"frame larger than {MAX_FRAME_BYTES} bytes"
            try:
                request = json.loads(text)
            except ValueError:
                return CloseCode.INVALID_PAYLOAD, "a frame is not JSON"
            if not isinstance(request, dict):
                return CloseCode.INVALID_PAYLOAD, "a rosbridge request is a JSON object with an op"
            session.handle(request)
    except (WebSocketDisconnect, RuntimeError):
        return None
    return None


async def _send_loop(websocket: WebSocket, session: RosbridgeSession) -> None:
    loop = asyncio.get_running_loop()
    try:
        while True:
            session.ready.clear()  # before looking, so a message arriving meanwhile sets it again
            text, wait_s = session.next_frame(loop.time())
            if text is not None:
                await websocket.send_text(text)
                continue
            with contextlib.suppress(TimeoutError):
                await asyncio.wait_for(session.ready.wait(), wait_s)
    except (WebSocketDisconnect, RuntimeError):
        return
