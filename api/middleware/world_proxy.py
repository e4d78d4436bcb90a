"""A class server's calls for a world that runs on a world worker go to that worker.

The class server keeps the student's page, the join form, the instructor's page and every
access check (token, world, write limit) for itself; what acts on a world (``/api/...``, the
page's views, and every WebSocket: keys, echo, rosbridge, the 3D view) is passed on to the
worker that hosts it, naming the world. The student's cookie and token never leave the class
server: a student's call goes on with a credential for their world alone
(``world_call_token``), which the worker answers as that world's student; only the instructor's
own calls go on as the instructor. The path goes on exactly as it was checked: one a normaliser
would change never gets here (api/middleware/canonical_path.py), and the URL sent must carry the same path.
A worker that does not answer is a 502 (HTTP) or close 1011 (WebSocket) that says so; a closed
world's socket keeps its worker's close code (1012 on a reset). A world's workspace routes go on
like the rest: a worker that keeps the files in a folder of its own is kept in step with the
class's copy (server/classroom/workspace_copies.py).
"""

from __future__ import annotations

from urllib.parse import parse_qsl, urlencode

import httpx
import websockets
from fastapi import WebSocket, status
from starlette.requests import HTTPConnection
from starlette.types import ASGIApp, Message, Receive, Scope, Send

from api.deps import SAFE_METHODS, WORLD_HEADER, token_of
from api.errors import CloseCode, close_reason
from api.protocol.json_codec import SafeJSONResponse
from api.websockets.relay import relay
from server.classroom import Classroom, ClassroomError, Grant, World
from server.classroom.class_bridges import CLASS_ROSBRIDGE_PATH
from server.classroom.worker_connections import WorkerCallError
from server.classroom.workers import WorkerDirectory, WorkerRef, world_call_token

# Hop-by-hop headers, and what the class server answers for itself (who the caller is, where from).
DROP_REQUEST = frozenset(
    {
        "host",
        "cookie",
        "authorization",
        WORLD_HEADER,
        "origin",
        "referer",
        "connection",
        "keep-alive",
        "te",
        "trailer",
        "transfer-encoding",
        "upgrade",
        "content-length",
        "proxy-authorization",
    }
)
DROP_RESPONSE = frozenset({"connection", "keep-alive", "transfer-encoding", "set-cookie", "server", "date"})
WS_OPEN_TIMEOUT_S = 10.0
# The class server's own sockets: the instructor's rosbridge on the class domain, the class view.
CLASS_SOCKETS = frozenset({CLASS_ROSBRIDGE_PATH, "/instructor/view"})


class PathChanged(ValueError):
    """The URL to a worker would carry another path than the one that was checked."""


def passed_on(scope: Scope) -> bool:
    """Whether a request acts on a world (and so goes where the world runs)."""
    path: str = scope["path"]
    if scope["type"] == "websocket":
        return path not in CLASS_SOCKETS
    if path.startswith("/api/classroom/") or path == "/api/classroom":
        return False
    return path.startswith("/api/") or path == "/page/views"


class WorldProxyMiddleware:
    def __init__(self, app: ASGIApp) -> None:
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        classroom: Classroom | None = None
        if scope["type"] in ("http", "websocket"):
            classroom = getattr(scope["app"].state, "classroom", None)
        # Only a class server has workers to pass a call on to (a world worker's ``workers`` is None).
        if classroom is None or classroom.workers is None or not passed_on(scope):
            await self.app(scope, receive, send)
            return
        conn = HTTPConnection(scope)
        grant = classroom.grant(token_of(conn))
        world: World | None = None
        if grant is not None:
            try:
                world = classroom.world_for(
                    grant, conn.headers.get(WORLD_HEADER) or conn.query_params.get("world")
                )
            except ClassroomError:
                world = None  # the route refuses it, as for any world
        if world is None or world.worker is None:
            await self.app(scope, receive, send)
            return
        directory = classroom.workers
        if world.lost is not None:  # its worker is gone; it starts again elsewhere shortly
            if scope["type"] == "websocket":
                await WebSocket(scope, receive, send).close(
                    status.WS_1013_TRY_AGAIN_LATER, close_reason(world.lost)
                )
            else:
                await SafeJSONResponse({"detail": world.lost}, status.HTTP_503_SERVICE_UNAVAILABLE)(
                    scope, receive, send
                )
            return
        assert grant is not None
        if scope["type"] == "websocket":
            await _forward_ws(directory, grant, world, world.worker, scope, receive, send)
            return
        if scope["method"] not in SAFE_METHODS and not grant.is_instructor and not world.writes.take():
            detail = (
                f"too many requests for world {world.name!r}: at most "
                f"{classroom.class_settings.world.writes_hz:g} writes a second"
            )
            await SafeJSONResponse({"detail": detail}, status.HTTP_429_TOO_MANY_REQUESTS)(
                scope, receive, send
            )
            return
        await _forward_http(directory, grant, world, world.worker, scope, receive, send)


def target(ref: WorkerRef, scope: Scope, websocket: bool) -> str:
    """The worker's URL for this request: the path as sent, the query without the caller's token
    and world. PathChanged if the URL, as a client parses it, would name another path."""
    raw_path = scope.get("raw_path")
    path = raw_path.decode("latin-1") if isinstance(raw_path, bytes) else scope["path"]
    query = [
        (k, v)
        for k, v in parse_qsl(scope["query_string"].decode("latin-1"), keep_blank_values=True)
        if k not in ("token", "world")
    ]
    base = ref.url.replace("http", "ws", 1) if websocket else ref.url
    url = base + path + (f"?{urlencode(query)}" if query else "")
    if httpx.URL(url).raw_path.split(b"?", 1)[0] != path.encode("latin-1"):
        raise PathChanged(f"the path {path!r} would reach the world worker as another path")
    return url


def credential(directory: WorkerDirectory, grant: Grant, world: World, ref: WorkerRef) -> str:
    """What a call goes on to the worker with: the instructor's calls as the instructor, a
    student's with a credential for their own world only."""
    if grant.is_instructor:
        return ref.token
    return world_call_token(directory.class_token, ref.id, world.name)


def _headers(scope: Scope, token: str, world: World) -> list[tuple[str, str]]:
    kept = [
        (k.decode("latin-1"), v.decode("latin-1"))
        for k, v in scope["headers"]
        if k.decode("latin-1").lower() not in DROP_REQUEST and not k.lower().startswith(b"sec-websocket")
    ]
    return [*kept, ("authorization", f"Bearer {token}"), (WORLD_HEADER, world.name)]


async def _read_body(receive: Receive) -> bytes | None:
    body = bytearray()
    while True:
        message: Message = await receive()
        if message["type"] == "http.disconnect":
            return None
        body += message.get("body", b"")
        if not message.get("more_body"):
            return bytes(body)


async def _forward_http(
    directory: WorkerDirectory,
    grant: Grant,
    world: World,
    ref: WorkerRef,
    scope: Scope,
    receive: Receive,
    send: Send,
) -> None:
    try:
        url = target(ref, scope, websocket=False)
    except PathChanged as exc:
        await SafeJSONResponse({"detail": str(exc)}, status.HTTP_400_BAD_REQUEST)(scope, receive, send)
        return
    body = await _read_body(receive)  # the guard outside has already capped its size
    if body is None:
        return
    sent = _headers(scope, credential(directory, grant, world, ref), world)
    try:
        answer = await directory.connections.request(scope["method"], url, sent, body)
    except WorkerCallError as exc:
        detail = f"world {world.name!r} runs on world worker {ref.id!r}, which did not answer: {exc}"
        await SafeJSONResponse({"detail": detail}, status.HTTP_502_BAD_GATEWAY)(scope, receive, send)
        return
    try:
        headers = [(k, v) for k, v in answer.headers if k.decode("latin-1") not in DROP_RESPONSE]
        await send({"type": "http.response.start", "status": answer.status, "headers": headers})
        async for chunk in answer.body():
            await send({"type": "http.response.body", "body": chunk, "more_body": True})
        await send({"type": "http.response.body", "body": b"", "more_body": False})
    finally:
        await answer.aclose()


async def _forward_ws(
    directory: WorkerDirectory,
    grant: Grant,
    world: World,
    ref: WorkerRef,
    scope: Scope,
    receive: Receive,
    send: Send,
) -> None:
    websocket = WebSocket(scope, receive, send)
    subprotocols = scope.get("subprotocols") or None
    token = credential(directory, grant, world, ref)
    headers = [(k, v) for k, v in _headers(scope, token, world) if k.lower() != "user-agent"]
    try:
        url = target(ref, scope, websocket=True)
    except PathChanged as exc:
        await websocket.close(CloseCode.BAD_REQUEST, close_reason(str(exc)))
        return
    try:
        upstream = await websockets.connect(
            url,
            subprotocols=subprotocols,
            additional_headers=headers,
            max_size=None,
            compression=None,
            open_timeout=WS_OPEN_TIMEOUT_S,
            proxy=None,
        )
    except websockets.exceptions.InvalidStatus as exc:
        # The worker refused it before opening (an unknown topic, a full lab): say so in its words.
        code = (
            status.WS_1008_POLICY_VIOLATION
            if exc.response.status_code < 500
            else status.WS_1011_INTERNAL_ERROR
        )
        await websocket.close(code, close_reason(f"world {world.name!r}: the world worker refused: {exc}"))
        return
    except (OSError, TimeoutError, ValueError, websockets.exceptions.WebSocketException) as exc:
        await websocket.close(
            status.WS_1011_INTERNAL_ERROR,
            close_reason(f"world {world.name!r}'s worker {ref.id!r} did not answer: {exc}"),
        )
        return
    await relay(websocket, upstream)
