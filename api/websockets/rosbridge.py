"""WebSocket: the rosbridge v2 endpoint at ``/rosbridge`` (roslibjs, roslibpy), behind the app's guard.

On a class server ``/rosbridge`` is a world's (the student's own; the instructor names one with
``?world=``), and ``/class/rosbridge`` is the instructor's: the class's own domain, every world's
topics under its name (server/classroom/class_bridges.py), as the class's ``--rosbridge-port``.

The protocol is server/services/bridges/rosbridge.py; here are its transport and its limits. Frames are
JSON text; a binary frame, a frame that is not a JSON object, or one over the size limit closes
the connection with a close code that says which. A task of its own sends, so a client that
reads slowly only loses the oldest messages of its subscriptions.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
from dataclasses import dataclass

from fastapi import APIRouter, WebSocket, WebSocketDisconnect, WebSocketException

from api.deps import WsLabDep, classroom_of, token_of
from api.errors import CloseCode, close_reason
from api.websockets.budget import spend
from api.websockets.life import closed_when, closed_when_lab_stops
from node_runtime.limits import RateLimit
from server.base.tasks import cancel_and_wait
from server.classroom.class_bridges import CLASS_ROSBRIDGE_PATH, world_topic
from server.services.bridges.rosbridge import RosbridgeSession

router = APIRouter(tags=["websockets"])
CLASS_STOPS = "the class server stops"
MAX_FRAME_BYTES = 1 << 20  # a publish of the largest message any lab type can hold fits


@router.websocket("/rosbridge")
async def rosbridge(websocket: WebSocket, lab: WsLabDep) -> None:
    await websocket.accept()
    budget = Budget(lab.socket_frames, lab.socket_requests)
    await _serve(websocket, RosbridgeSession(lab.bus), closed_when_lab_stops(websocket, lab), budget)


@router.websocket(CLASS_ROSBRIDGE_PATH)
async def class_rosbridge(websocket: WebSocket) -> None:
    """The instructor's rosbridge on the class's own domain: ``/ada/uav/sensors/gps`` and the like."""
    classroom = classroom_of(websocket)
    if classroom is None:
        raise _refused(CloseCode.NOT_FOUND, "not a class server: use /rosbridge")
    grant = classroom.grant(token_of(websocket))
    if grant is None:
        raise _refused(CloseCode.UNAUTHORIZED, "the instructor's token is needed")
    if not grant.is_instructor:
        raise _refused(
            CloseCode.FORBIDDEN, "the class's rosbridge is the instructor's: a student's is /rosbridge"
        )
    bridges = classroom.bridges  # None: not up, or a world worker's (its class server has the class's)
    if bridges is None:
        raise _refused(CloseCode.TRY_AGAIN_LATER, "the class's graph is not up (no Zenoh router)")
    await websocket.accept()
    session = RosbridgeSession(bridges.bus, limits_name=world_topic)
    await _serve(
        websocket, session, closed_when(websocket, bridges.closed, CloseCode.GOING_AWAY, CLASS_STOPS)
    )


def _refused(code: int, reason: str) -> WebSocketException:
    """The handshake refused with a close code that names why, as a world's sockets are refused."""
    return WebSocketException(code, close_reason(reason))


@dataclass(frozen=True)
class Budget:
    """The lab's WebSocket budgets this session spends: frames it sends, requests it takes."""

    frames: RateLimit | None = None
    requests: RateLimit | None = None


async def _serve(
    websocket: WebSocket,
    session: RosbridgeSession,
    lifetime: contextlib.AbstractAsyncContextManager[None],
    budget: Budget = Budget(),
) -> None:
    """Run an accepted client's session until it leaves, breaks a rule, or ``lifetime`` closes it."""
    sender = asyncio.create_task(_send_loop(websocket, session, budget.frames))
    try:
        async with lifetime:
            close = await _receive_loop(websocket, session, budget.requests)
    finally:
        await cancel_and_wait(sender)
        session.close()
    if close is not None:
        with contextlib.suppress(RuntimeError, WebSocketDisconnect):
            await websocket.close(*close)


async def _receive_loop(
    websocket: WebSocket, session: RosbridgeSession, requests: RateLimit | None
) -> tuple[int, str] | None:
    """Handle requests until the client leaves (None) or must be closed (code, reason)."""
    try:
        while (frame := await websocket.receive())["type"] != "websocket.disconnect":
            await spend(requests)
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


async def _send_loop(websocket: WebSocket, session: RosbridgeSession, frames: RateLimit | None) -> None:
    loop = asyncio.get_running_loop()
    try:
        while True:
            session.ready.clear()  # before looking, so a message arriving meanwhile sets it again
            text, wait_s = session.next_frame(loop.time())
            if text is not None:
                await spend(frames)  # over the lab's budget this session waits, one frame in hand
                await websocket.send_text(text)
                continue
            with contextlib.suppress(TimeoutError):
                await asyncio.wait_for(session.ready.wait(), wait_s)
    except (WebSocketDisconnect, RuntimeError):
        return
