"""A channel that only sends (topic echo, a run's output): the first frame a client sends ends the
socket with a close code that names what was wrong, a frame over the limit as too big."""

from __future__ import annotations

from fastapi import WebSocket, WebSocketDisconnect

from api.errors import CloseCode


async def refuse_client_frames(websocket: WebSocket, max_frame_bytes: int, channel: str) -> None:
    """Wait for the client's first frame and close with a named code; return when it disconnects."""
    try:
        frame = await websocket.receive()
        if frame["type"] == "websocket.disconnect":
            return
        data = frame.get("text") or frame.get("bytes") or b""
        if len(data) > max_frame_bytes:
            await websocket.close(CloseCode.MESSAGE_TOO_BIG, f"frame larger than {max_frame_bytes} bytes")
        else:
            await websocket.close(CloseCode.UNSUPPORTED_DATA, f"the {channel} channel takes no messages")
    except (WebSocketDisconnect, RuntimeError):
        return
