"""A world worker's API socket (server/world_worker.py, ``listening_socket``) gives connections
that send small writes at once. The worker binds its socket before its app starts; asyncio turns
Nagle's algorithm off on a server's connections only when the listening socket is TCP by name,
and with it on, a call the class server passed on over a kept-alive connection waited about 40 ms
for its last bytes. Served here as uvicorn serves it (an asyncio server on the given socket), and
beside it a socket made as the worker made it before, whose connections keep Nagle's algorithm on."""

from __future__ import annotations

import asyncio
import socket

import pytest

from server.world_worker import listening_socket

WAIT_S = 10.0


async def nodelay_of_a_connection(sock: socket.socket) -> int:
    """TCP_NODELAY on the server's side of one connection made to ``sock``."""
    seen: asyncio.Future[int] = asyncio.get_running_loop().create_future()

    def accepted(_: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        raw = writer.get_extra_info("socket")
        seen.set_result(raw.getsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY))
        writer.close()

    server = await asyncio.start_server(accepted, sock=sock)
    async with server:
        host, port = sock.getsockname()[:2]
        _, writer = await asyncio.open_connection(host, port)
        try:
            return await asyncio.wait_for(seen, WAIT_S)
        finally:
            writer.close()


def test_the_workers_connections_send_small_writes_at_once() -> None:
    assert asyncio.run(nodelay_of_a_connection(listening_socket("127.0.0.1", 0))) != 0


def test_a_socket_not_named_tcp_keeps_nagles_algorithm_on_its_connections() -> None:
    plain = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    plain.bind(("127.0.0.1", 0))
    assert asyncio.run(nodelay_of_a_connection(plain)) == 0


def test_a_port_in_use_is_refused() -> None:
    held = listening_socket("127.0.0.1", 0)
    try:
        held.listen()
        with pytest.raises(OSError):
            listening_socket("127.0.0.1", held.getsockname()[1])
    finally:
        held.close()
