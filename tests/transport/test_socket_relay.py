"""The relay a world worker on another machine opens for its sandboxed nodes: a Unix socket whose
connections go on to the router's TCP endpoint byte for byte, each end closing the other.

A TCP echo server on loopback stands in for the router (the Zenoh link itself is checked in
tests/classroom/test_worker_student_code.py, where a sandboxed node joins its world through it).
"""

from __future__ import annotations

import asyncio
import os
import socket
import socketserver
import threading

import pytest

from node_runtime.transport import socket_relay
from node_runtime.transport.socket_relay import SocketRelay, tcp_target

WAIT_S = 10.0


@pytest.mark.parametrize(
    ("endpoint", "target"),
    [
        ("tcp/127.0.0.1:7447", ("127.0.0.1", 7447)),
        ("tcp/[::1]:7447", ("::1", 7447)),
        ("tcp/router.example:7447#iface=eth0", ("router.example", 7447)),
        ("tls/127.0.0.1:7447", None),  # the node would have to speak TLS itself
        ("quic/127.0.0.1:7447", None),
        ("tcp/127.0.0.1", None),
        ("tcp/127.0.0.1:99999", None),
        ("tcp/:7447", None),
        (None, None),
    ],
)
def test_only_a_plain_tcp_endpoint_is_relayed(endpoint: str | None, target: tuple[str, int] | None) -> None:
    assert tcp_target(endpoint) == target


async def echo_server() -> tuple[asyncio.Server, int, list[asyncio.StreamWriter]]:
    """A TCP server on loopback that sends back what it gets; the list holds its connections."""
    accepted: list[asyncio.StreamWriter] = []

    async def echo(reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        accepted.append(writer)
        while data := await reader.read(65536):
            writer.write(data)
            await writer.drain()
        writer.close()

    server = await asyncio.start_server(echo, "127.0.0.1", 0)
    return server, server.sockets[0].getsockname()[1], accepted


def test_the_relay_carries_bytes_both_ways_and_cleans_up() -> None:
    async def scenario() -> None:
        server, port, accepted = await echo_server()
        relay = await SocketRelay.open("127.0.0.1", port)
        try:
            assert relay.path.is_socket()
            assert relay.path.stat().st_mode & 0o777 == 0o666  # a sandboxed node of another uid connects
            reader, writer = await asyncio.open_unix_connection(str(relay.path))
            payload = os.urandom(300_000)  # several chunks each way
            writer.write(payload)
            await writer.drain()
            echoed = await asyncio.wait_for(reader.readexactly(len(payload)), WAIT_S)
            assert echoed == payload and len(accepted) == 1 and relay.links == 1
            writer.close()  # the node's end closes: the relay closes its end to the router too
            await ended(relay)
        finally:
            await relay.close()
            server.close()
            await server.wait_closed()
        assert not relay.path.parent.exists()  # the socket's folder goes with it

    asyncio.run(scenario())


def test_a_router_that_goes_closes_the_nodes_link() -> None:
    async def scenario() -> None:
        server, port, accepted = await echo_server()
        relay = await SocketRelay.open("127.0.0.1", port)
        try:
            reader, writer = await asyncio.open_unix_connection(str(relay.path))
            writer.write(b"ping")
            assert await asyncio.wait_for(reader.readexactly(4), WAIT_S) == b"ping"
            server.close()
            accepted[0].close()  # the router ends the link
            assert await asyncio.wait_for(reader.read(), WAIT_S) == b""  # end of stream, not a hang
            await ended(relay)
            writer.close()
        finally:
            await relay.close()
            await server.wait_closed()

    asyncio.run(scenario())


def test_no_router_there_closes_the_link_at_once() -> None:
    async def scenario() -> None:
        server, port, _ = await echo_server()
        server.close()
        await server.wait_closed()  # nothing listens on the port now
        relay = await SocketRelay.open("127.0.0.1", port)
        try:
            reader, writer = await asyncio.open_unix_connection(str(relay.path))
            assert await asyncio.wait_for(reader.read(), WAIT_S) == b""
            writer.close()
        finally:
            await relay.close()

    asyncio.run(scenario())


def test_links_past_the_limit_are_closed_and_the_others_keep_working(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(socket_relay, "MAX_LINKS", 2)

    async def scenario() -> None:
        server, port, accepted = await echo_server()
        relay = await SocketRelay.open("127.0.0.1", port)
        try:
            links = [await asyncio.open_unix_connection(str(relay.path)) for _ in range(2)]
            for reader, writer in links:  # both carried through
                writer.write(b"x")
                assert await asyncio.wait_for(reader.readexactly(1), WAIT_S) == b"x"
            reader3, writer3 = await asyncio.open_unix_connection(str(relay.path))
            assert await asyncio.wait_for(reader3.read(), WAIT_S) == b""  # the third is closed
            writer3.close()
            reader, writer = links[0]
            writer.write(b"y")  # and the first still carries
            assert await asyncio.wait_for(reader.readexactly(1), WAIT_S) == b"y"
            assert len(accepted) == 2
            for _, link in links:
                link.close()
        finally:
            await relay.close()
            server.close()
            await server.wait_closed()

    asyncio.run(scenario())


class _Echo(socketserver.BaseRequestHandler):
    ended = threading.Event()  # set when the relay closed its link to this router

    def handle(self) -> None:
        while data := self.request.recv(65536):
            self.request.sendall(data)
        _Echo.ended.set()


class _Router(socketserver.ThreadingTCPServer):
    daemon_threads = True
    block_on_close = False  # a link left open fails the test below; it never hangs it


def test_the_relay_carries_while_the_loop_that_opened_it_is_busy() -> None:
    """The worlds' loop opens the relay; the nodes' traffic must not wait for that loop's turn. A
    client and a router on threads of their own exchange bytes through the relay while the loop
    that opened it is blocked (joining the client's thread): they get through only if the relay
    runs elsewhere."""
    _Echo.ended.clear()
    with _Router(("127.0.0.1", 0), _Echo) as router:
        threading.Thread(target=router.serve_forever, daemon=True).start()
        got: list[bytes] = []

        def node(path: str) -> None:
            with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as link:
                link.settimeout(WAIT_S)
                link.connect(path)
                link.sendall(b"ping")
                got.append(link.recv(4))

        async def scenario() -> None:
            relay = await SocketRelay.open("127.0.0.1", router.server_address[1])
            try:
                client = threading.Thread(target=node, args=(str(relay.path),))
                client.start()
                client.join(WAIT_S)  # blocks this loop: no turn for anything on it
                assert got == [b"ping"]
            finally:
                await relay.close()
            assert not relay.path.parent.exists()
            assert _Echo.ended.wait(WAIT_S)  # its link to the router closed with it

        try:
            asyncio.run(scenario())
        finally:
            router.shutdown()


async def ended(relay: SocketRelay) -> None:
    """Until every link the relay carries has ended."""
    await asyncio.wait_for(relay.drained(), WAIT_S)
    assert relay.links == 0
