"""Carry one WebSocket to another server and back: the 3D view's to viser, and a worker's world's
to its world worker. Frames pass unchanged both ways; whichever side closes first, the other is
told why (never just dropped)."""

from __future__ import annotations

import asyncio
import contextlib

import websockets
from fastapi import WebSocket, WebSocketDisconnect, status
from websockets.asyncio.client import ClientConnection

from server.base.tasks import cancel_and_wait


async def relay(websocket: WebSocket, upstream: ClientConnection, max_frame_bytes: int | None = None) -> None:
    """Accept ``websocket`` with the subprotocol upstream chose and pump frames until one side ends."""
    async with upstream:
        await websocket.accept(subprotocol=upstream.subprotocol)

        async def client_to_upstream() -> tuple[int, str] | None:
            """Pump until the browser leaves (None) or must be closed (code, reason)."""
            while (message := await websocket.receive())["type"] != "websocket.disconnect":
                data = message.get("bytes") if message.get("bytes") is not None else message.get("text")
                if data is None:
                    return status.WS_1003_UNSUPPORTED_DATA, "empty frame"
                if max_frame_bytes is not None and len(data) > max_frame_bytes:
                    return status.WS_1009_MESSAGE_TOO_BIG, f"frame larger than {max_frame_bytes} bytes"
                try:
                    await upstream.send(data)
                except websockets.exceptions.ConnectionClosed:
                    return upstream_close(upstream)
            return None

        async def upstream_to_client() -> tuple[int, str]:
            with contextlib.suppress(websockets.exceptions.ConnectionClosed):
                async for data in upstream:
                    if isinstance(data, bytes):
                        await websocket.send_bytes(data)
                    else:
                        await websocket.send_text(data)
            return upstream_close(upstream)

        tasks = [asyncio.create_task(client_to_upstream()), asyncio.create_task(upstream_to_client())]
        try:
            done, _ = await asyncio.wait(tasks, return_when=asyncio.FIRST_COMPLETED)
        finally:
            await cancel_and_wait(*tasks)
    first = next(iter(done))
    close = first.result() if first.exception() is None else (status.WS_1011_INTERNAL_ERROR, "relay failed")
    if close is not None:  # the browser is still there: tell it why, never just drop the connection
        with contextlib.suppress(RuntimeError, WebSocketDisconnect):
            await websocket.close(*close)


def upstream_close(upstream: ClientConnection) -> tuple[int, str]:
    """The far side's close code and reason, as a code a server may send (1005/1006/1015 may not be)."""
    code = upstream.close_code
    if code is None or code in (1005, 1006, 1015):
        code = status.WS_1011_INTERNAL_ERROR
    return code, upstream.close_reason or "the far side closed the connection"
