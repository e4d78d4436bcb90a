"""A WebSocket opening handshake written by hand, for what a `websockets` client will not send:
one Host header naming another site (a DNS-rebinding page), duplicated headers."""

from __future__ import annotations

import asyncio

READ_S = 10.0


async def _send_handshake(
    port: int, path: str, headers: tuple[tuple[str, str], ...]
) -> tuple[asyncio.StreamReader, asyncio.StreamWriter]:
    """Connect to 127.0.0.1:``port`` and send a WebSocket opening handshake with ``headers``."""
    reader, writer = await asyncio.open_connection("127.0.0.1", port)
    lines = [f"GET {path} HTTP/1.1", *(f"{k}: {v}" for k, v in headers)]
    lines += [
        "Upgrade: websocket",
        "Connection: Upgrade",
        "Sec-WebSocket-Version: 13",
        "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==",
    ]
    writer.write(("\r\n".join(lines) + "\r\n\r\n").encode())
    return reader, writer


async def handshake_status(port: int, path: str = "/", headers: tuple[tuple[str, str], ...] = ()) -> int:
    """The HTTP status a server on 127.0.0.1:``port`` answers a WebSocket handshake with."""
    reader, writer = await _send_handshake(port, path, headers)
    try:
        status_line = await asyncio.wait_for(reader.readline(), READ_S)
        return int(status_line.split()[1])
    finally:
        writer.close()


async def handshake_refusal(port: int, path: str = "/", headers: tuple[tuple[str, str], ...] = ()) -> int:
    """How a server on 127.0.0.1:``port`` refuses a WebSocket handshake: the close code of the
    first frame after a completed handshake (the app's rule for every WebSocket route), or the
    HTTP status of a handshake it does not complete. Fails if a completed one sends anything but
    a close first."""
    reader, writer = await _send_handshake(port, path, headers)
    try:
        async with asyncio.timeout(READ_S):
            head = await reader.readuntil(b"\r\n\r\n")
            status = int(head.split(b" ", 2)[1])
            if status != 101:
                return status
            first, length = await reader.readexactly(2)
            assert first & 0x0F == 0x8, f"the server sent a frame of opcode {first & 0x0F} before any close"
            payload = await reader.readexactly(length & 0x7F)  # a server's frames are not masked
            return int.from_bytes(payload[:2], "big")
    finally:
        writer.close()
