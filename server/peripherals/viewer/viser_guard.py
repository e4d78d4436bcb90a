"""viser's own port admits only the app's proxy.

viser listens on a loopback port of its own, and checks neither Origin nor Host: a page from any
site could open a WebSocket to it and use the page's panels (fly the drone). So the display
gives viser a secret that only the app's proxy knows and sends (``PROXY_TOKEN_HEADER``); a
request without it, or with an Origin (every browser sends one; the proxy never does), is
answered 403 before viser sees it, HTTP or WebSocket alike.

viser 1.1.1 has no hook for this, so while the ViserServer is built (its constructor returns
once its server is listening), ``websockets.asyncio.server.serve`` is swapped for a subclass that
wraps viser's ``process_request``. A test connects to viser's port directly to prove it.
"""

from __future__ import annotations

import hmac
import inspect
import secrets
from collections.abc import Awaitable, Callable, Iterator
from contextlib import contextmanager
from http import HTTPStatus
from typing import Any

import websockets.asyncio.server as ws_server
from websockets.asyncio.server import ServerConnection
from websockets.http11 import Request, Response

PROXY_TOKEN_HEADER = "X-Teleop-Proxy-Token"
ProcessRequest = Callable[[ServerConnection, Request], Awaitable[Response | None] | Response | None]


def new_token() -> str:
    return secrets.token_urlsafe(32)


def admits(token: str, headers: Any) -> bool:
    """Only the proxy: the secret, and no Origin header."""
    supplied = str(headers.get(PROXY_TOKEN_HEADER, ""))
    return hmac.compare_digest(supplied.encode(), token.encode()) and headers.get("Origin") is None


def checked(token: str, inner: ProcessRequest | None) -> ProcessRequest:
    async def process_request(connection: ServerConnection, request: Request) -> Response | None:
        if not admits(token, request.headers):
            return connection.respond(HTTPStatus.FORBIDDEN, "only the lab app's proxy may connect here\n")
        if inner is None:
            return None
        result = inner(connection, request)
        return await result if inspect.isawaitable(result) else result

    return process_request


@contextmanager
def guarded_serve(token: str) -> Iterator[None]:
    """While open, every websockets server started (viser's) admits only requests carrying ``token``."""
    original = ws_server.serve

    class GuardedServe(original):  # type: ignore[misc, valid-type]
        def __init__(self, *args: Any, process_request: ProcessRequest | None = None, **kwargs: Any) -> None:
            super().__init__(*args, process_request=checked(token, process_request), **kwargs)

    ws_server.serve = GuardedServe  # type: ignore[misc]
    try:
        yield
    finally:
        ws_server.serve = original  # type: ignore[misc]
