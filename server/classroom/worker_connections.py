"""The calls a class server passes on to its world workers, over kept HTTP/1.1 connections spoken
with h11 on asyncio's streams.

Every call a student's page makes to a world a worker hosts goes through the class server
(api/middleware/world_proxy.py), on the loop where the class server's own worlds tick. Through
httpx each took that loop about twice what answering a call of its own took (its connection
pool's locks and async-library sniffing, its request and response models), none of it needed to
carry one request on and stream its answer back; this way, about half (bench/proxied_calls.py).
A worker's connections are kept open (at most ``MAX_IDLE`` a worker, none idle longer than
``MAX_IDLE_S``, well inside uvicorn's 5 s keep-alive, and none its worker has closed), a call
goes out on one of them, and the answer's body is handed on as it arrives. A connection goes back
only after a whole exchange; any other end (an error, a body left unread, a worker that closes)
closes it.
"""

from __future__ import annotations

import asyncio
import contextlib
import time
from collections.abc import AsyncGenerator, Callable
from dataclasses import dataclass, field
from urllib.parse import urlsplit

import h11

MAX_IDLE = 16  # idle connections kept a worker
MAX_IDLE_S = 2.0  # an idle connection older than this is closed, not used
MAX_OPEN = 64  # connections at once to one worker; more calls wait for one
READ_CHUNK = 65536


class WorkerCallError(Exception):
    """The worker could not be reached, or broke off before its answer's head."""


@dataclass
class _Connection:
    reader: asyncio.StreamReader
    writer: asyncio.StreamWriter
    h11: h11.Connection = field(default_factory=lambda: h11.Connection(h11.CLIENT))
    idle_since: float = 0.0

    def usable(self, now: float) -> bool:
        return (
            now - self.idle_since <= MAX_IDLE_S and not self.reader.at_eof() and not self.writer.is_closing()
        )

    def close(self) -> None:
        with contextlib.suppress(Exception):
            self.writer.close()


class WorkerAnswer:
    """The head of a worker's answer; ``body()`` streams the rest and then gives the connection
    back (or closes it); ``aclose()`` ends it, read or not (always call it)."""

    def __init__(
        self,
        status: int,
        headers: list[tuple[bytes, bytes]],
        body: AsyncGenerator[bytes, None],
        release: Callable[[], None],
    ) -> None:
        self.status, self.headers = status, headers
        self._body, self._release = body, release

    def body(self) -> AsyncGenerator[bytes, None]:
        return self._body

    async def aclose(self) -> None:
        try:
            await self._body.aclose()
        finally:
            self._release()


class _Origin:
    """One worker's address: its idle connections and how many are open."""

    def __init__(self, host: str, port: int, ssl: bool) -> None:
        self.host, self.port, self.ssl = host, port, ssl
        self.idle: list[_Connection] = []
        self.open = asyncio.Semaphore(MAX_OPEN)


class WorkerConnections:
    """Kept connections to the workers, by address; ``clock`` is monotonic seconds."""

    def __init__(self, timeout_s: float, clock: Callable[[], float] = time.monotonic) -> None:
        if not timeout_s > 0:
            raise ValueError(f"timeout_s must be positive, got {timeout_s!r}")
        self.timeout_s = timeout_s
        self.clock = clock
        self._origins: dict[tuple[str, int, bool], _Origin] = {}
        self.opened = 0  # connections opened so far (a kept one is opened once)

    def _origin(self, url: str) -> tuple[_Origin, str, str]:
        """The worker's address, its ``host[:port]`` and the request target: everything after the
        address, exactly as written (the path as it was checked, and the query)."""
        parts = urlsplit(url)
        if parts.scheme not in ("http", "https") or not parts.hostname:
            raise WorkerCallError(f"not a worker's address: {url!r}")
        ssl = parts.scheme == "https"
        port = parts.port or (443 if ssl else 80)
        key = (parts.hostname, port, ssl)
        origin = self._origins.get(key)
        if origin is None:
            origin = self._origins[key] = _Origin(parts.hostname, port, ssl)
        return origin, parts.netloc, url[len(f"{parts.scheme}://{parts.netloc}") :]

    async def _connect(self, origin: _Origin) -> _Connection:
        now = self.clock()
        while origin.idle:
            conn = origin.idle.pop()
            if conn.usable(now):
                return conn
            conn.close()
        reader, writer = await asyncio.open_connection(origin.host, origin.port, ssl=origin.ssl or None)
        self.opened += 1
        return _Connection(reader, writer)

    async def request(
        self, method: str, url: str, headers: list[tuple[str, str]], body: bytes
    ) -> WorkerAnswer:
        """Send ``method`` ``url`` (its path and query as written) to its worker with ``headers``
        and ``body``; the answer's head, its body to stream. WorkerCallError if the worker cannot
        be reached or breaks off before its head, within ``timeout_s``."""
        origin, netloc, target = self._origin(url)
        try:
            async with asyncio.timeout(self.timeout_s):
                await origin.open.acquire()
        except TimeoutError:
            raise WorkerCallError(f"no connection to the worker free in {self.timeout_s:g} s") from None
        conn: _Connection | None = None
        released = False

        def release() -> None:  # once: the connection closed unless kept, the slot given back
            nonlocal released
            if not released:
                released = True
                if conn is not None:
                    conn.close()
                origin.open.release()

        try:
            async with asyncio.timeout(self.timeout_s):
                conn = await self._connect(origin)
                sent = [("host", netloc), *headers, ("content-length", str(len(body)))]
                wire = conn.h11.send(
                    h11.Request(method=method, target=target.encode("latin-1"), headers=sent)
                )
                if body:
                    wire += conn.h11.send(h11.Data(data=body))
                wire += conn.h11.send(h11.EndOfMessage())
                conn.writer.write(wire)
                await conn.writer.drain()
                head = await _head(conn)
        except (OSError, TimeoutError, EOFError, h11.ProtocolError) as exc:
            release()
            raise WorkerCallError(str(exc) or type(exc).__name__) from None
        except BaseException:
            release()
            raise
        kept = conn

        async def stream() -> AsyncGenerator[bytes, None]:
            nonlocal conn
            while True:
                event = kept.h11.next_event()
                if event is h11.NEED_DATA:
                    async with asyncio.timeout(self.timeout_s):
                        kept.h11.receive_data(await kept.reader.read(READ_CHUNK))
                elif isinstance(event, h11.Data):
                    yield bytes(event.data)
                elif isinstance(event, h11.EndOfMessage | h11.ConnectionClosed):
                    break
            if (
                kept.h11.our_state is h11.DONE
                and kept.h11.their_state is h11.DONE
                and len(origin.idle) < MAX_IDLE
            ):
                kept.h11.start_next_cycle()
                kept.idle_since = self.clock()
                origin.idle.append(kept)
                conn = None  # kept open: release() gives the slot back and leaves it be
            release()

        return WorkerAnswer(head.status_code, list(head.headers), stream(), release)

    def close(self) -> None:
        for origin in self._origins.values():
            for conn in origin.idle:
                conn.close()
            origin.idle.clear()


async def _head(conn: _Connection) -> h11.Response:
    """The head of the worker's answer (past any informational one, as 100 Continue)."""
    while True:
        event = conn.h11.next_event()
        if event is h11.NEED_DATA:
            data = await conn.reader.read(READ_CHUNK)
            if not data:  # (h11 would say so as a state it cannot handle)
                raise EOFError("the worker closed the connection before it answered")
            conn.h11.receive_data(data)
        elif isinstance(event, h11.Response):
            return event
