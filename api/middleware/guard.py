"""Safe by default: only this machine's host names, no cross-site writes, bounded bodies.

A page on another site must never be able to fly the drone: WebSockets and state-changing
requests carrying another site's Origin are refused, and a Host header that is not a name of
this machine (DNS rebinding) is refused outright. The rules themselves are server/base/access.py's,
which the bridges' guarded fronts apply too.
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterable

from starlette.types import ASGIApp, Message, Receive, Scope, Send

from api.errors import BodyTooLarge
from server.base.access import host_allowed, origin_allowed
from server.base.close_codes import CLOSE_FOR_STATUS, refuse_socket

SAFE_METHODS = frozenset({"GET", "HEAD", "OPTIONS"})


def _header(scope: Scope, name: bytes) -> str | None:
    for key, value in scope.get("headers", []):
        if key == name:
            return str(value, "latin-1")
    return None


class GuardMiddleware:
    """Host check for everything; Origin check for WebSockets and writes; a cap on body size
    (``larger_bodies``: path prefixes with a cap of their own, such as a workspace's uploads)."""

    def __init__(
        self,
        app: ASGIApp,
        accepted_hosts: Iterable[str],
        allowed_origins: Iterable[str],
        max_body_bytes: int,
        larger: Iterable[tuple[re.Pattern[str], int]] = (),
    ) -> None:
        self.app = app
        self.accepted_hosts = frozenset(accepted_hosts)
        self.allowed_origins = frozenset(allowed_origins)
        self.max_body_bytes = max_body_bytes
        self.larger = tuple(larger)  # (a path, matched whole; its own limit): an image, a report

    def limit_for(self, path: str) -> int:
        return next((limit for pattern, limit in self.larger if pattern.fullmatch(path)), self.max_body_bytes)

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] not in ("http", "websocket"):
            return await self.app(scope, receive, send)
        host = _header(scope, b"host")
        if not host_allowed(host, self.accepted_hosts):
            return await self._refuse(scope, send, 421, f"host {host!r} is not a name of this server")
        cross_site = not origin_allowed(_header(scope, b"origin"), host, self.allowed_origins)
        if cross_site and (scope["type"] == "websocket" or scope["method"] not in SAFE_METHODS):
            return await self._refuse(scope, send, 403, "cross-site origin refused")
        if scope["type"] == "http" and scope["method"] not in SAFE_METHODS:
            limit = self.limit_for(scope["path"])
            length = _header(scope, b"content-length")
            if length is not None and length.isdigit() and int(length) > limit:
                return await self._refuse(scope, send, 413, f"body larger than {limit} bytes")
            receive = self._bounded(receive, limit)
        await self.app(scope, receive, send)

    def _bounded(self, receive: Receive, limit: int) -> Receive:
        seen = 0

        async def bounded() -> Message:
            nonlocal seen
            message = await receive()
            seen += len(message.get("body", b""))
            if seen > limit:
                raise BodyTooLarge(limit)
            return message

        return bounded

    async def _refuse(self, scope: Scope, send: Send, status: int, detail: str) -> None:
        if scope["type"] == "websocket":  # api/middleware/socket_refusal.py: the code arrives, not a bare 403
            await refuse_socket(send, CLOSE_FOR_STATUS[status], detail)
            return
        body = json.dumps({"detail": detail}).encode()
        await send(
            {
                "type": "http.response.start",
                "status": status,
                "headers": [
                    (b"content-type", b"application/json"),
                    (b"content-length", str(len(body)).encode()),
                ],
            }
        )
        await send({"type": "http.response.body", "body": body})
