"""Safe by default: only this machine's host names, no cross-site writes, bounded bodies.

A page on another site must never be able to fly the drone: WebSockets and state-changing
requests carrying another site's Origin are refused, and a Host header that is not a name of
this machine (DNS rebinding) is refused outright.
"""

from __future__ import annotations

import hmac
import json
from collections.abc import Iterable
from urllib.parse import urlsplit

from starlette.exceptions import HTTPException
from starlette.types import ASGIApp, Message, Receive, Scope, Send

from .close_codes import REFUSAL_FOR_STATUS

SAFE_METHODS = frozenset({"GET", "HEAD", "OPTIONS"})


def _host_name(host_header: str) -> str:
    host = host_header.strip().lower()
    if host.startswith("["):  # [::1]:8000
        return host[1:].split("]", 1)[0]
    return host.rsplit(":", 1)[0] if host.count(":") == 1 else host


def host_allowed(host_header: str | None, accepted: Iterable[str]) -> bool:
    return host_header is not None and _host_name(host_header) in set(accepted)


def origin_allowed(origin: str | None, host_header: str | None, allowed_origins: Iterable[str]) -> bool:
    """No Origin (a non-browser client) or the page's own origin; anything else must be listed."""
    if origin is None:
        return True
    if origin in set(allowed_origins):
        return True
    parts = urlsplit(origin)
    if parts.scheme not in ("http", "https") or not parts.netloc or host_header is None:
        return False
    return parts.netloc.lower() == host_header.strip().lower()


def bearer_token(authorization: str | None) -> str | None:
    """The token of an ``Authorization: Bearer TOKEN`` header, else None."""
    auth = authorization or ""
    return auth[7:].strip() if auth[:7].lower() == "bearer " else None


def token_matches(given: str | None, expected: str) -> bool:
    """Compared in constant time, so the answer's timing tells nothing of the token."""
    return given is not None and hmac.compare_digest(given.encode(), expected.encode())


def _header(scope: Scope, name: bytes) -> str | None:
    for key, value in scope.get("headers", []):
        if key == name:
            return str(value, "latin-1")
    return None


class GuardMiddleware:
    """Host check for everything; Origin check for WebSockets and writes; a cap on body size."""

    def __init__(
        self, app: ASGIApp, accepted_hosts: Iterable[str], allowed_origins: Iterable[str], max_body_bytes: int
    ) -> None:
        self.app = app
        self.accepted_hosts = frozenset(accepted_hosts)
        self.allowed_origins = frozenset(allowed_origins)
        self.max_body_bytes = max_body_bytes

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
            length = _header(scope, b"content-length")
            if length is not None and length.isdigit() and int(length) > self.max_body_bytes:
                return await self._refuse(scope, send, 413, f"body larger than {self.max_body_bytes} bytes")
            receive = self._bounded(receive)
        await self.app(scope, receive, send)

    def _bounded(self, receive: Receive) -> Receive:
        seen = 0

        async def bounded() -> Message:
            nonlocal seen
            message = await receive()
            seen += len(message.get("body", b""))
            if seen > self.max_body_bytes:
                raise BodyTooLarge(self.max_body_bytes)
            return message

        return bounded

    async def _refuse(self, scope: Scope, send: Send, status: int, detail: str) -> None:
        if scope["type"] == "websocket":  # api/ws_refusal.py: the close code arrives, not a bare 403
            await send({"type": "websocket.close", "code": REFUSAL_FOR_STATUS[status], "reason": detail})
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


class BodyTooLarge(HTTPException):
    """Raised while a body without Content-Length is read; an HTTPException so that FastAPI's
    body parser re-raises it (any other exception there becomes a 400 "error parsing the body")."""

    def __init__(self, limit: int) -> None:
        self.limit = limit
        super().__init__(413, f"body larger than {limit} bytes")

    def __str__(self) -> str:
        return str(self.detail)
