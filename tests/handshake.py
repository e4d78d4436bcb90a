"""A WebSocket opening handshake written by hand, for what a `websockets` client will not send:
one Host header naming another site (a DNS-rebinding page), duplicated headers."""

from __future__ import annotations

import asyncio

READ_S = 10.0


async def handshake_status(port: int, path: str = "/", headers: tuple[tuple[str, str], ...] = ()) -> int:
    """The HTTP status a server on 127.0.0.1:``port`` answers a WebSocket handshake with."""
    reader, writer = await asyncio.open_connection("127.0.0.1", port)
    try:
        lines = [f"GET {path} HTTP/1.1", *(f"{k}: {v}" for k, v in headers)]
        lines += ["Upgrade: websocket", "Connection: Upgrade", "Sec-WebSocket-Version: 13",
                  "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ=="]  # fmt: skip
        writer.write(("\r\n".join(lines) + "\r\n\r\n").encode())
        status_line = await asyncio.wait_for(reader.readline(), READ_S)
        return int(status_line.split()[1])
    finally:
        writer.close()
