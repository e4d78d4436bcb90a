"""The guarded front before a WebSocket server the app cannot configure checks what upstream will
read: a head two parsers could read differently, or a path a normaliser would change, is refused
and never reaches upstream; a plain handshake with the token goes through byte for byte.

A real front and a recording upstream on loopback ports; each refused head is followed by a
plain one, which is the only one upstream sees."""

from __future__ import annotations

import asyncio

import pytest

from server.services.bridges.front import GuardedFront

TOKEN = "front-token"
WAIT_S = 10.0
REFUSED = {
    "GET /./?token=front-token HTTP/1.1\r\n": "dot segment",
    "GET //evil.example/?token=front-token HTTP/1.1\r\n": "empty segment",
    "GET /%2e%2e/?token=front-token HTTP/1.1\r\n": "'%2e'",
    "GET /?token=front-token&token=other HTTP/1.1\r\n": "more than one token",
    "GET / HTTP/1.1\r\nAuthorization: Bearer front-token\r\nAuthorization: Bearer other\r\n": "authorization",
    "GET /?token=front-token HTTP/1.1\r\nX-A: b\nOrigin: http://evil.example\r\n": "bare line break",
}
PLAIN = "GET /?token=front-token HTTP/1.1\r\n"


def _head(start: str, port: int) -> bytes:
    rest = f"Host: 127.0.0.1:{port}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n\r\n"
    return (start + rest).encode("latin-1")


async def _exchange(port: int, head: bytes) -> bytes:
    reader, writer = await asyncio.open_connection("127.0.0.1", port)
    writer.write(head)
    await writer.drain()
    answer = await asyncio.wait_for(reader.read(), WAIT_S)
    writer.close()
    await writer.wait_closed()
    return answer


async def _run(refused: str) -> tuple[bytes, bytes, list[bytes], int]:
    heads: list[bytes] = []

    async def upstream(reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        heads.append(await reader.readuntil(b"\r\n\r\n"))
        writer.write(b"HTTP/1.1 101 Switching Protocols\r\n\r\n")
        await writer.drain()
        writer.close()

    server = await asyncio.start_server(upstream, "127.0.0.1", 0)
    up_port = int(server.sockets[0].getsockname()[1])
    front = GuardedFront("127.0.0.1", 0, up_port, ["127.0.0.1"], (), token=TOKEN)
    port = await front.start()
    try:
        refusal = await _exchange(port, _head(refused, port))
        passed = await _exchange(port, _head(PLAIN, port))  # the marker: the only head upstream sees
    finally:
        await front.stop()
        server.close()
        await server.wait_closed()
    return refusal, passed, heads, front.refused


@pytest.mark.parametrize(("start", "named"), REFUSED.items())
def test_a_head_upstream_could_read_otherwise_is_refused_and_never_sent(start: str, named: str) -> None:
    refusal, passed, heads, refused = asyncio.run(_run(start))
    assert refusal.startswith(b"HTTP/1.1 400"), refusal
    assert named.encode() in refusal, refusal
    assert passed.startswith(b"HTTP/1.1 101"), passed
    assert len(heads) == 1 and heads[0].startswith(PLAIN.encode()), heads
    assert refused == 1
