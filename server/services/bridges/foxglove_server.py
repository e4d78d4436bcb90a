"""The Foxglove WebSocket server: the one listener Foxglove and Lichtblick reach, guarded as the app is.

foxglove-sdk's own server checks neither Origin nor Host nor any token, and opens a TCP port that
anyone on the machine can reach; it has no hook to check a handshake. So the app speaks the
protocol itself (server/services/bridges/foxglove_protocol.py) on the ``websockets`` server it already uses,
and applies the app's rules (server/services/bridges/front.py ``check_handshake``: a Host that names this
machine, no Origin of another site, the lab's or the instructor's token) to every handshake
before a byte of the protocol is sent. A refused one is closed at once with the close code that
names why (api/middleware/socket_refusal.py's rule). No other port serves Foxglove.

Everything runs on the app's loop. Each client has one bounded queue of frames: a message it is
too slow for is dropped (and counted); a client too slow even for the server's announcements is
closed. Clients are bounded in number.
"""

from __future__ import annotations

import asyncio
import contextlib
import itertools
import logging
import secrets
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from typing import Protocol

from websockets.asyncio.server import Server, ServerConnection, serve
from websockets.exceptions import ConnectionClosed
from websockets.typing import Subprotocol

from server.base.close_codes import CLOSE_FOR_STATUS, CloseCode
from server.base.tasks import cancel_and_wait
from server.services.bridges import foxglove_protocol as proto
from server.services.bridges.front import HandshakeRefused, check_handshake, single_headers

log = logging.getLogger("bridges.foxglove")
MESSAGE_BACKLOG = 1024  # frames queued for one client (the SDK's default backlog)
MAX_CLIENTS = 64
MAX_FRAME_BYTES = 1 << 20  # a client's message: the largest message any lab type holds fits
SUPPORTED_ENCODINGS = ("cdr", "json")


class ChannelSource(Protocol):
    """What the server asks of the bridge node (server/services/bridges/foxglove.py)."""

    def channel_list(self) -> list[proto.ChannelInfo]: ...
    def client_subscribed(self, channel_id: int) -> None: ...
    def client_unsubscribed(self, channel_id: int) -> None: ...
    def client_message(self, channel: proto.ClientChannel, data: bytes) -> str | None: ...


@dataclass(frozen=True)
class Guard:
    """The app's rules for a handshake (api/middleware/guard.py), and the token it needs, if any."""

    accepted_hosts: frozenset[str]
    allowed_origins: frozenset[str]
    token: str | None


@dataclass(eq=False)
class Session:
    """One connected client: its queue, its subscriptions and the channels it advertised."""

    ws: ServerConnection
    queue: asyncio.Queue[str | bytes] = field(default_factory=lambda: asyncio.Queue(MESSAGE_BACKLOG))
    subscriptions: dict[int, int] = field(default_factory=dict)  # subscription id → channel id
    by_channel: dict[int, int] = field(default_factory=dict)  # channel id → subscription id
    advertised: dict[int, proto.ClientChannel] = field(default_factory=dict)
    dropped: int = 0
    too_slow: bool = False

    def send_control(self, frame: str) -> None:
        try:
            self.queue.put_nowait(frame)
        except asyncio.QueueFull:
            self.too_slow = True  # its sender closes it

    def send_data(self, frame: bytes) -> None:
        try:
            self.queue.put_nowait(frame)
        except asyncio.QueueFull:
            self.dropped += 1


class FoxgloveServer:
    """``await start(host, port)`` listens; ``advertise``/``unadvertise``/``log`` reach every client."""

    def __init__(self, name: str, source: ChannelSource, guard: Guard) -> None:
        self.name = name
        self.source = source
        self.guard = guard
        self.session_id = secrets.token_hex(8)
        self.sessions: set[Session] = set()
        self.refused = 0
        self.port = 0
        self._server: Server | None = None
        self._ids = itertools.count(1)

    async def start(self, host: str, port: int) -> int:
        """Listen (OSError if ``port`` is taken); returns the port (useful when asked for 0)."""
        self._server = await serve(
            self._serve,
            host,
            port,
            select_subprotocol=_select_subprotocol,
            max_size=MAX_FRAME_BYTES,
            compression=None,
            server_header=None,
        )
        self.port = int(next(iter(self._server.sockets)).getsockname()[1])
        return self.port

    async def stop(self) -> None:
        if self._server is not None:
            self._server.close()
            await self._server.wait_closed()

    # -- from the bridge node ------------------------------------------------
    def advertise(self, channel: proto.ChannelInfo) -> None:
        frame = proto.advertise([channel])
        for session in self.sessions:
            session.send_control(frame)

    def unadvertise(self, channel_id: int) -> None:
        """A channel is gone: its subscriptions with it (the node already stopped feeding it)."""
        frame = proto.unadvertise([channel_id])
        for session in self.sessions:
            sub_id = session.by_channel.pop(channel_id, None)
            if sub_id is not None:
                del session.subscriptions[sub_id]
            session.send_control(frame)

    def log(self, channel_id: int, payload: bytes, log_time_ns: int) -> None:
        for session in self.sessions:
            sub_id = session.by_channel.get(channel_id)
            if sub_id is not None:
                session.send_data(proto.message_data(sub_id, log_time_ns, payload))

    # -- a client ------------------------------------------------------------
    async def _serve(self, ws: ServerConnection) -> None:
        refusal = self._refusal(ws)
        if refusal is not None:
            self.refused += 1
            await ws.close(*refusal)
            return
        session = Session(ws)
        channels = self.source.channel_list()  # before it is a session: its channels once, here
        self.sessions.add(session)
        session.send_control(proto.server_info(self.name, self.session_id, SUPPORTED_ENCODINGS))
        if channels:
            session.send_control(proto.advertise(channels))
        sender = asyncio.create_task(self._send(session))
        try:
            async for frame in ws:
                self._receive(session, frame)
        except ConnectionClosed:
            pass
        finally:
            self.sessions.discard(session)
            for channel_id in session.by_channel:
                self.source.client_unsubscribed(channel_id)
            await cancel_and_wait(sender)

    def _refusal(self, ws: ServerConnection) -> tuple[int, str] | None:
        request = ws.request
        if request is None:  # pragma: no cover - the handler runs only after a handshake
            return CloseCode.BAD_REQUEST, "no handshake"
        try:
            headers = single_headers(request.headers.raw_items())
            check_handshake(
                f"GET {request.path} HTTP/1.1",
                headers,
                self.guard.accepted_hosts,
                self.guard.allowed_origins,
                self.guard.token,
            )
        except HandshakeRefused as exc:
            return CLOSE_FOR_STATUS.get(exc.status, CloseCode.BAD_REQUEST), exc.reason
        if len(self.sessions) >= MAX_CLIENTS:
            return CloseCode.TRY_AGAIN_LATER, f"already {MAX_CLIENTS} Foxglove clients here"
        return None

    async def _send(self, session: Session) -> None:
        with contextlib.suppress(ConnectionClosed):
            while not session.too_slow:
                frame = await session.queue.get()
                await session.ws.send(frame)
            await session.ws.close(CloseCode.TRY_AGAIN_LATER, "too slow: the server's messages piled up")

    def _receive(self, session: Session, frame: str | bytes) -> None:
        try:
            if isinstance(frame, bytes):
                channel_id, payload = proto.client_data(frame)
                self._client_message(session, channel_id, payload)
            else:
                self._client_op(session, proto.client_op(frame))
        except proto.ProtocolError as exc:
            session.send_control(proto.status(proto.StatusLevel.ERROR, str(exc)))

    def _client_message(self, session: Session, channel_id: int, payload: bytes) -> None:
        channel = session.advertised.get(channel_id)
        if channel is None:
            raise proto.ProtocolError(f"no channel {channel_id} advertised by this client")
        problem = self.source.client_message(channel, payload)
        if problem is not None:
            session.send_control(proto.status(proto.StatusLevel.WARNING, problem[:500]))

    def _client_op(self, session: Session, op: proto.ClientOp) -> None:
        if isinstance(op, proto.Subscribe):
            self._subscribe(session, op.subscriptions)
        elif isinstance(op, proto.Unsubscribe):
            for sub_id in op.subscription_ids:
                channel_id = session.subscriptions.pop(sub_id, None)
                if channel_id is not None:
                    del session.by_channel[channel_id]
                    self.source.client_unsubscribed(channel_id)
        elif isinstance(op, proto.Advertise):
            session.advertised.update((c.id, c) for c in op.channels)
        else:
            for channel_id in op.channel_ids:
                session.advertised.pop(channel_id, None)

    def _subscribe(self, session: Session, subscriptions: Iterable[tuple[int, int]]) -> None:
        known = {c.id for c in self.source.channel_list()}
        for sub_id, channel_id in subscriptions:
            if channel_id not in known:
                raise proto.ProtocolError(f"no channel {channel_id} here")
            if sub_id in session.subscriptions or channel_id in session.by_channel:
                raise proto.ProtocolError(
                    f"subscription {sub_id} or channel {channel_id} is subscribed already"
                )
            session.subscriptions[sub_id] = channel_id
            session.by_channel[channel_id] = sub_id
            self.source.client_subscribed(channel_id)


def _select_subprotocol(ws: ServerConnection, offered: Sequence[Subprotocol]) -> Subprotocol | None:
    """The client's first offer this server speaks; none if it offers none (a refused client's
    handshake still completes, to carry its close code)."""
    return next((s for s in offered if s in proto.SUBPROTOCOLS), None)
