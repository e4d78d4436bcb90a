"""Every request's path as sent is the path that is checked, routed and forwarded.

A path that a normaliser would change (a client library, a reverse proxy, the class server's own
call to a world worker) could be checked as one route and answered as another: the class server
would authorise ``/api/./classroom/worlds`` as a world's call and a hop behind it would answer
``/api/classroom/worlds``. So such a path is refused, with a 400 that names what is wrong, before
anything reads it: dot segments (``.``, ``..``), empty segments (``//``), backslashes, and
percent-encoded dots, slashes and backslashes (which some servers decode into separators). The
console gets one warning line per refusal (the path only, escaped: a token is never in it).
"""

from __future__ import annotations

import json
import logging

from starlette.types import ASGIApp, Receive, Scope, Send

from api.errors import CloseCode
from server.base.access import path_problem
from server.base.close_codes import refuse_socket

log = logging.getLogger("api.paths")
BAD_REQUEST = 400
LOGGED_PATH_CHARS = 200


def _raw_path(scope: Scope) -> bytes:
    raw = scope.get("raw_path")
    return raw if isinstance(raw, bytes) and raw else str(scope["path"]).encode("utf-8")


class CanonicalPathMiddleware:
    """Refuse (400) any HTTP request or WebSocket handshake whose path is not in canonical form."""

    def __init__(self, app: ASGIApp) -> None:
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] not in ("http", "websocket"):
            await self.app(scope, receive, send)
            return
        raw = _raw_path(scope)
        problem = path_problem(raw)
        if problem is None:
            await self.app(scope, receive, send)
            return
        shown = repr(raw.decode("latin-1")[:LOGGED_PATH_CHARS])
        method = scope.get("method", "WEBSOCKET")
        log.warning("refused %s %s from %s: %s", method, shown, _client(scope), problem)
        detail = f"{problem}: send the path in canonical form"
        await _refuse(scope, send, detail)


def _client(scope: Scope) -> str:
    client = scope.get("client")
    return f"{client[0]}" if client else "an unknown client"


async def _refuse(scope: Scope, send: Send, detail: str) -> None:
    body = json.dumps({"detail": detail}).encode()
    headers = [(b"content-type", b"application/json"), (b"content-length", str(len(body)).encode())]
    if scope["type"] == "http":
        await send({"type": "http.response.start", "status": BAD_REQUEST, "headers": headers})
        await send({"type": "http.response.body", "body": body})
    elif "websocket.http.response" in scope.get("extensions", {}):
        # The handshake answered with the same 400 and body as a plain request.
        await send({"type": "websocket.http.response.start", "status": BAD_REQUEST, "headers": headers})
        await send({"type": "websocket.http.response.body", "body": body})
    else:  # a server without that extension answers a close before accept with its own 403
        await refuse_socket(send, CloseCode.BAD_REQUEST, detail)
