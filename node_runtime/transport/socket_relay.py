"""A Unix socket that carries each connection on to a Zenoh router's TCP endpoint, byte for byte.

A sandboxed node has no network: it reaches its router through a Unix socket bound into the
sandbox (router_socket.py). A world worker on another machine than the class server has no such
socket of the class's router, so it opens this one and relays every connection to the endpoint it
joined the router on. Zenoh's stream links (TCP and ``unixsock-stream``) carry the same framing, so
the node's session and the router see an ordinary link; the router still asks each session for its
login. Only a plain ``tcp/`` endpoint can be relayed: over TLS or QUIC the node would have to speak
that itself, and a node in a sandbox cannot.

The relay runs on an event loop of its own, in a thread of its own, so the nodes' traffic never
takes a turn of the loop that runs the worker's worlds. Each direction is read in bounded chunks
and written with back-pressure, so a slow end slows its own link only; connections past
``MAX_LINKS`` are closed at once.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import threading
from collections.abc import Coroutine
from pathlib import Path
from typing import Any, TypeVar

from node_runtime.transport.router_socket import new_socket_path, open_to_nodes, remove

log = logging.getLogger("transport.socket_relay")

CHUNK = 64 * 1024
MAX_LINKS = 256  # a worker's sandboxed nodes at once (each node process holds one link)
CONNECT_TIMEOUT_S = 5.0
STOP_WAIT_S = 5.0
T = TypeVar("T")


def tcp_target(endpoint: str | None) -> tuple[str, int] | None:
    """(host, port) of a plain ``tcp/HOST:PORT`` Zenoh endpoint (``[v6]`` allowed), else None."""
    if endpoint is None or not endpoint.startswith("tcp/"):
        return None
    address = endpoint[len("tcp/") :].split("#", 1)[0]
    host, sep, port = address.rpartition(":")
    if not sep or not host or not port.isdigit() or not 0 < int(port) < 65536:
        return None
    return host.strip("[]"), int(port)


class SocketRelay:
    """One Unix socket (``path``) whose connections go on to ``host:port``, on a thread of its own."""

    def __init__(self, host: str, port: int) -> None:
        self.host = host
        self.port = port
        self.path: Path = new_socket_path()
        self._server: asyncio.Server | None = None
        self._links: set[asyncio.Task[None]] = set()
        self._loop = asyncio.new_event_loop()
        self._thread = threading.Thread(target=self._loop.run_forever, name="router relay", daemon=True)

    @classmethod
    async def open(cls, host: str, port: int) -> SocketRelay:
        relay = cls(host, port)
        relay._thread.start()
        try:
            await relay._on_own_loop(relay._listen())
        except OSError:
            await relay._end_thread()
            remove(relay.path)
            raise
        open_to_nodes(relay.path)
        log.info("sandboxed nodes reach the router at tcp/%s:%d through %s", host, port, relay.path)
        return relay

    @property
    def links(self) -> int:
        """Connections being carried now."""
        return len(self._links)

    async def drained(self) -> None:
        """Until every link being carried now has ended."""
        await self._on_own_loop(self._gather_links())

    async def _on_own_loop(self, work: Coroutine[Any, Any, T]) -> T:
        return await asyncio.wrap_future(asyncio.run_coroutine_threadsafe(work, self._loop))

    async def _listen(self) -> None:
        self._server = await asyncio.start_unix_server(self._accept, path=str(self.path))

    async def _gather_links(self) -> None:
        await asyncio.gather(*list(self._links), return_exceptions=True)

    async def _accept(self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        if len(self._links) >= MAX_LINKS:
            log.warning("relay to the router full (%d links): a connection was closed", MAX_LINKS)
            writer.close()
            return
        task = asyncio.current_task()
        assert task is not None
        self._links.add(task)
        try:
            await self._carry(reader, writer)
        finally:
            self._links.discard(task)

    async def _carry(self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        try:
            far_reader, far_writer = await asyncio.wait_for(
                asyncio.open_connection(self.host, self.port), CONNECT_TIMEOUT_S
            )
        except (OSError, TimeoutError) as exc:
            log.warning("relay to the router at tcp/%s:%d: %s", self.host, self.port, exc)
            writer.close()
            return
        pumps = [
            asyncio.create_task(_pump(reader, far_writer)),
            asyncio.create_task(_pump(far_reader, writer)),
        ]
        try:
            # Either end closing ends the link: the other is closed too.
            await asyncio.wait(pumps, return_when=asyncio.FIRST_COMPLETED)
        finally:
            for pump in pumps:
                pump.cancel()
            await asyncio.gather(*pumps, return_exceptions=True)
            for end in (writer, far_writer):
                end.close()
            for end in (writer, far_writer):  # closed for real before the relay's loop may stop
                with contextlib.suppress(OSError):
                    await end.wait_closed()

    async def close(self) -> None:
        """Stop accepting, end every link, end the relay's thread and remove the socket's folder."""
        if self._thread.is_alive():
            await self._on_own_loop(self._shutdown())
            await self._end_thread()
        remove(self.path)

    async def _shutdown(self) -> None:
        if self._server is not None:
            self._server.close()
            self._server = None
        links = list(self._links)
        for link in links:
            link.cancel()
        await asyncio.gather(*links, return_exceptions=True)

    async def _end_thread(self) -> None:
        self._loop.call_soon_threadsafe(self._loop.stop)
        await asyncio.to_thread(self._thread.join, STOP_WAIT_S)
        if not self._thread.is_alive():
            self._loop.close()


async def _pump(source: asyncio.StreamReader, sink: asyncio.StreamWriter) -> None:
    with contextlib.suppress(OSError):
        while chunk := await source.read(CHUNK):
            sink.write(chunk)
            await sink.drain()
