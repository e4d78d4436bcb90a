"""WebSocket: ``/ws/launches/{id}/output`` streams what a launch's or run's node processes print.

Frames (JSON text): ``line`` (``seq``, ``node``, ``stream``, ``text``), ``dropped`` (``count``:
lines a fast printer lost before this socket read them), ``waiting`` (``node``: a node process
that waits for its turn to start, on a server that starts a few at a time), ``started``
(``node``, ``pid``: the process runs), ``joined`` (``node``, ``names``: its node is in the lab's
graph; the page shows it as starting until then), ``exit`` (``node``, ``code`` or ``signal``;
neither for one stopped before it started) and, once every node of the group has ended, ``end``,
after which the server closes the socket (1000). A new socket first gets the lines still kept. The output is read from the
processes' own bounded buffers every ``POLL_S``, so a flood costs this socket no memory and
the lab nothing; the lab's frame budget paces the sends. An unknown id closes with 4404; the
channel takes no messages.
"""

from __future__ import annotations

import asyncio

from fastapi import APIRouter, WebSocket, WebSocketDisconnect

from api.deps import WsLabDep
from api.errors import CloseCode, close_reason
from api.protocol.json_codec import dumps
from api.websockets.budget import spend
from api.websockets.life import closed_when_lab_stops
from api.websockets.send_only import refuse_client_frames
from server.services.launch.groups import UnknownLaunchError
from server.services.launch.output import GroupOutput
from server.world.lab import Lab

router = APIRouter(tags=["websockets"])
POLL_S = 0.05
ENDED_REASON = "every node of the group has ended"


@router.websocket("/ws/launches/{group_id}/output")
async def output(websocket: WebSocket, group_id: str, lab: WsLabDep) -> None:
    await websocket.accept()
    try:
        group = lab.launch_groups.get(group_id)
    except UnknownLaunchError as exc:
        await websocket.close(CloseCode.NOT_FOUND, close_reason(str(exc)))
        return
    reader = GroupOutput(group, lambda: group_id in lab.launch_groups, lab.joined_names)
    sender = asyncio.create_task(_send_loop(websocket, reader, lab))
    try:
        async with closed_when_lab_stops(websocket, lab):
            await refuse_client_frames(websocket, lab.settings.listen.max_ws_frame_bytes, "output")
    finally:
        sender.cancel()
        await asyncio.gather(sender, return_exceptions=True)


async def _send_loop(websocket: WebSocket, reader: GroupOutput, lab: Lab) -> None:
    try:
        while not reader.ended:
            for frame in reader.poll():
                await spend(lab.socket_frames)
                await websocket.send_text(dumps(frame))
            if not reader.ended:
                await asyncio.sleep(POLL_S)
        await websocket.close(1000, ENDED_REASON)
    except (WebSocketDisconnect, RuntimeError, asyncio.CancelledError):
        return
