"""A guarded front door onto a WebSocket route of the app: rosbridge on a port of its own.

It listens where clients connect (``--rosbridge-port``), reads the opening handshake, applies the
app's own rules (server/base/access.py: a Host that names this machine, no Origin of another site, the
token, a path as sent) and only then joins the client to the app's port,
byte for byte in both directions.
A refused WebSocket handshake completes and is closed at once with the close code that names why
(4401, 4403, 4421: api/middleware/socket_refusal.py's rule for every route), and never reaches upstream; a
request that is no WebSocket handshake gets an HTTP 400 or 426. Nothing here parses the frames
that follow, so the protocol stays upstream's. ``check_handshake`` is also the Foxglove server's.

What is checked is what upstream reads: a head that two parsers could read differently (a bare
line break, two Hosts or Authorizations, two ``token`` parameters) is refused, not guessed at.
"""

from __future__ import annotations

import asyncio
import base64
import contextlib
import hashlib
import logging
import struct
from collections.abc import Iterable
from urllib.parse import parse_qs, urlsplit

from server.base.access import bearer_token, host_allowed, origin_allowed, path_problem, token_matches
from server.base.close_codes import CLOSE_FOR_STATUS, HANDSHAKE_REFUSALS
from server.base.tasks import cancel_and_wait

log = logging.getLogger("bridges.front")
MAX_HEAD_BYTES = 16 * 1024
HEAD_TIMEOUT_S = 10.0
CHUNK_BYTES = 64 * 1024
SINGLE_HEADERS = frozenset({"host", "origin", "upgrade", "authorization"})
WS_GUID = "258EAFA5-E914-47DA-95CA-C5AB0DC85B11"  # RFC 6455's, for Sec-WebSocket-Accept
CLOSE_WAIT_S = 2.0  # how long a refused client has to answer the close


class HandshakeRefused(Exception):
    def __init__(self, status: int, reason: str) -> None:
        super().__init__(reason)
        self.status = status
        self.reason = reason


def parse_head(head: bytes) -> tuple[str, dict[str, str]]:
    """The request line and the headers (lower-cased names) of an HTTP/1.1 request head."""
    try:
        text = head.decode("latin-1")
    except UnicodeDecodeError:  # pragma: no cover - latin-1 decodes any byte
        raise HandshakeRefused(400, "unreadable request") from None
    unfolded = text.replace("\r\n", "")
    if "\x00" in text or "\n" in unfolded or "\r" in unfolded:  # parsers differ on these: refuse
        raise HandshakeRefused(400, "a bare line break or NUL in the request head")
    request_line, *lines = text.split("\r\n")
    items: list[tuple[str, str]] = []
    for line in lines:
        if not line:
            continue
        name, sep, value = line.partition(":")
        if not sep:
            raise HandshakeRefused(400, "malformed header line")
        items.append((name, value))
    return request_line, single_headers(items)


def single_headers(items: Iterable[tuple[str, str]]) -> dict[str, str]:
    """Headers by lower-cased name; HandshakeRefused if one that must be single comes twice."""
    headers: dict[str, str] = {}
    for name, value in items:
        key = name.strip().lower()
        if key in headers and key in SINGLE_HEADERS:  # two Hosts: which one would upstream believe?
            raise HandshakeRefused(400, f"more than one {key} header")
        headers[key] = value.strip()
    return headers


def check_handshake(
    request_line: str,
    headers: dict[str, str],
    accepted_hosts: Iterable[str],
    allowed_origins: Iterable[str],
    token: str | None = None,
) -> None:
    """The app's rules for a WebSocket handshake; HandshakeRefused says which one failed."""
    parts = request_line.split(" ")
    if len(parts) != 3 or parts[0] != "GET" or not parts[2].startswith("HTTP/1."):
        raise HandshakeRefused(400, "only a WebSocket handshake (GET ... HTTP/1.1) is served here")
    if headers.get("upgrade", "").lower() != "websocket":
        raise HandshakeRefused(426, "this port speaks WebSocket only")
    problem = path_problem(parts[1].split("?", 1)[0].encode("latin-1"))
    if problem is not None:
        raise HandshakeRefused(400, f"{problem}: send the path in canonical form")
    host = headers.get("host")
    if not host_allowed(host, accepted_hosts):
        raise HandshakeRefused(421, f"host {host!r} is not a name of this server")
    if not origin_allowed(headers.get("origin"), host, allowed_origins):
        raise HandshakeRefused(403, "cross-site origin refused")
    if token is not None and not _carries_token(parts[1], headers, token):
        raise HandshakeRefused(401, "this lab needs its token: ?token=... or Authorization: Bearer")


def _carries_token(target: str, headers: dict[str, str], token: str) -> bool:
    given = bearer_token(headers.get("authorization"))
    if given is None:
        tokens = parse_qs(urlsplit(target).query).get("token", [])
        if len(tokens) > 1:  # upstream may read another one than the one checked here
            raise HandshakeRefused(400, "more than one token parameter")
        given = tokens[0] if tokens else None
    return token_matches(given, token)


class GuardedFront:
    """``await start()`` listens; each accepted connection is checked, then piped to upstream."""

    def __init__(
        self,
        host: str,
        port: int,
        upstream_port: int,
        accepted_hosts: Iterable[str],
        allowed_origins: Iterable[str],
        upstream_path: str | None = None,
        token: str | None = None,
    ) -> None:
        """``upstream_path``: the path every handshake is sent to upstream (rosbridge's port
        serves at ``/``, the app at ``/rosbridge``); None keeps the client's."""
        self.host = host
        self.upstream_path = upstream_path
        self.port = port
        self.upstream_port = upstream_port
        self.accepted_hosts = frozenset(accepted_hosts)
        self.allowed_origins = frozenset(allowed_origins)
        self.token = token
        self.refused = 0
        self._server: asyncio.Server | None = None
        self._tasks: set[asyncio.Task[None]] = set()

    async def start(self) -> int:
        """Listen; returns the port (useful when asked for port 0)."""
        self._server = await asyncio.start_server(self._serve, self.host, self.port)
        self.port = int(self._server.sockets[0].getsockname()[1])
        return self.port

    async def stop(self) -> None:
        if self._server is not None:
            self._server.close()
        await cancel_and_wait(*self._tasks)
        if self._server is not None:
            await self._server.wait_closed()

    async def _serve(self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        task = asyncio.current_task()
        if task is not None:
            self._tasks.add(task)
        try:
            await self._handle(reader, writer)
        finally:
            if task is not None:
                self._tasks.discard(task)
            writer.close()
            with contextlib.suppress(Exception):
                await writer.wait_closed()

    async def _handle(self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        try:
            head = await asyncio.wait_for(reader.readuntil(b"\r\n\r\n"), HEAD_TIMEOUT_S)
        except (asyncio.IncompleteReadError, asyncio.LimitOverrunError, TimeoutError, ConnectionError):
            return
        headers: dict[str, str] = {}
        try:
            if len(head) > MAX_HEAD_BYTES:
                raise HandshakeRefused(431, "request head too large")
            request_line, headers = parse_head(head[:-4])
            check_handshake(request_line, headers, self.accepted_hosts, self.allowed_origins, self.token)
        except HandshakeRefused as exc:
            self.refused += 1
            await _refuse(reader, writer, exc, headers)
            return
        try:
            up_reader, up_writer = await asyncio.open_connection("127.0.0.1", self.upstream_port)
        except OSError:
            down = HandshakeRefused(502, "the server behind this port is not running")
            await _refuse(reader, writer, down, headers)
            return
        up_writer.write(self._upstream_head(head, request_line))
        try:
            await _pipe_both(reader, writer, up_reader, up_writer)
        finally:
            up_writer.close()
            with contextlib.suppress(Exception):
                await up_writer.wait_closed()

    def _upstream_head(self, head: bytes, request_line: str) -> bytes:
        if self.upstream_path is None:
            return head
        method, target, version = request_line.split(" ")
        query = urlsplit(target).query  # a ?token= goes on to the app, which checks it too
        path = f"{self.upstream_path}?{query}" if query else self.upstream_path
        return f"{method} {path} {version}".encode("latin-1") + head[len(request_line) :]


async def _refuse(
    reader: asyncio.StreamReader, writer: asyncio.StreamWriter, exc: HandshakeRefused, headers: dict[str, str]
) -> None:
    """A WebSocket handshake: completed, then closed with the refusal's close code. Anything
    else: an HTTP error status."""
    key = headers.get("sec-websocket-key", "")
    # a door's refusal, or an upstream that cannot be reached, closes the socket with its code
    code = CLOSE_FOR_STATUS[exc.status] if exc.status in HANDSHAKE_REFUSALS | {502} else None
    if code is None or headers.get("upgrade", "").lower() != "websocket" or len(key) != 24:
        await _refuse_http(writer, exc)
        return
    accept = base64.b64encode(hashlib.sha1((key + WS_GUID).encode()).digest()).decode()
    head = [
        "HTTP/1.1 101 Switching Protocols",
        "Upgrade: websocket",
        "Connection: Upgrade",
        f"Sec-WebSocket-Accept: {accept}",
    ]
    offered = headers.get("sec-websocket-protocol", "").split(",")[0].strip()
    if offered:  # a client that asked for a subprotocol gets it, so none fails before the close
        head.append(f"Sec-WebSocket-Protocol: {offered}")
    reason = close_reason_bytes(exc.reason)
    close = struct.pack("!BBH", 0x88, 2 + len(reason), code) + reason  # FIN + close, unmasked
    writer.write(("\r\n".join(head) + "\r\n\r\n").encode("latin-1") + close)
    with contextlib.suppress(ConnectionError, TimeoutError, asyncio.IncompleteReadError):
        await writer.drain()
        # Read the client's close (and anything before it) so that closing sends no reset that
        # could overtake the close frame.
        async with asyncio.timeout(CLOSE_WAIT_S):
            while await reader.read(CHUNK_BYTES):
                pass


def close_reason_bytes(text: str) -> bytes:
    """A close frame's reason: at most 123 bytes of UTF-8."""
    return text.encode("utf-8")[:123].decode("utf-8", "ignore").encode("utf-8")


async def _refuse_http(writer: asyncio.StreamWriter, exc: HandshakeRefused) -> None:
    body = exc.reason.encode()
    writer.write(
        f"HTTP/1.1 {exc.status} Refused\r\nContent-Type: text/plain\r\nContent-Length: {len(body)}\r\n"
        "Connection: close\r\n\r\n".encode()
        + body
    )
    with contextlib.suppress(ConnectionError):
        await writer.drain()


async def _copy(reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
    with contextlib.suppress(ConnectionError):
        while data := await reader.read(CHUNK_BYTES):
            writer.write(data)
            await writer.drain()  # a slow reader slows this copy; the SDK drops its own backlog
    with contextlib.suppress(OSError, RuntimeError):
        writer.write_eof()


async def _pipe_both(
    reader: asyncio.StreamReader,
    writer: asyncio.StreamWriter,
    up_reader: asyncio.StreamReader,
    up_writer: asyncio.StreamWriter,
) -> None:
    tasks = [asyncio.create_task(_copy(reader, up_writer)), asyncio.create_task(_copy(up_reader, writer))]
    try:
        await asyncio.wait(tasks, return_when=asyncio.FIRST_COMPLETED)
    finally:
        await cancel_and_wait(*tasks)
