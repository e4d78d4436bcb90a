"""A WebSocket's life is its lab's: when the lab stops (a class server resets or removes the
world, or the app shuts down), the socket is closed with 1012, so the page's channels reconnect
to the world's new lab (or learn, with a 4401, that it is gone) instead of talking to a dead one."""

from __future__ import annotations

import asyncio
import contextlib
from collections.abc import AsyncIterator

from fastapi import WebSocket, WebSocketDisconnect

from api.errors import CloseCode
from server.base.tasks import cancel_and_wait
from server.world.lab import Lab

STOPPED_REASON = "the lab restarted: reconnect (a class server reset or removed this world)"


@contextlib.asynccontextmanager
async def closed_when(
    websocket: WebSocket, event: asyncio.Event, code: int, reason: str
) -> AsyncIterator[None]:
    """Close ``websocket`` with ``code`` and ``reason`` once ``event`` is set (while inside)."""

    async def watch() -> None:
        await event.wait()
        with contextlib.suppress(RuntimeError, WebSocketDisconnect):
            await websocket.close(code, reason)

    watcher = asyncio.create_task(watch())
    try:
        yield
    finally:
        await cancel_and_wait(watcher)


def closed_when_lab_stops(websocket: WebSocket, lab: Lab) -> contextlib.AbstractAsyncContextManager[None]:
    return closed_when(websocket, lab.stopped, CloseCode.SERVICE_RESTART, STOPPED_REASON)
