"""The WebSocket close codes the app uses: RFC 6455's, and the app's own 4xxx, each 4000 plus the
HTTP status a request refused for the same reason gets."""

from __future__ import annotations

from collections.abc import Awaitable, Callable
from enum import IntEnum
from typing import Any


class CloseCode(IntEnum):
    """WebSocket close codes this API uses (RFC 6455 names; 4xxx are the app's own)."""

    NORMAL = 1000
    GOING_AWAY = 1001
    UNSUPPORTED_DATA = 1003
    INVALID_PAYLOAD = 1007
    POLICY_VIOLATION = 1008
    MESSAGE_TOO_BIG = 1009
    INTERNAL_ERROR = 1011
    SERVICE_RESTART = 1012  # the lab behind the socket stopped (a class server reset its world)
    TRY_AGAIN_LATER = 1013
    BAD_REQUEST = 4400
    UNAUTHORIZED = 4401  # a class server: no valid token
    FORBIDDEN = (
        4403  # not the caller's: another student's world, the instructor's socket, another site's page
    )
    NOT_FOUND = 4404  # an unknown topic (or node, service, bag), or a route this server does not serve
    TYPE_CONFLICT = 4409
    MISDIRECTED = 4421  # a Host that is not a name of this server (DNS rebinding)


# The one table from the HTTP status a request gets to the close code a WebSocket gets for the same
# reason: the API's errors, the guard's refusals and the bridges' fronts all read it.
CLOSE_FOR_STATUS: dict[int, CloseCode] = {
    400: CloseCode.BAD_REQUEST,
    401: CloseCode.UNAUTHORIZED,
    403: CloseCode.FORBIDDEN,
    404: CloseCode.NOT_FOUND,
    409: CloseCode.TYPE_CONFLICT,
    412: CloseCode.BAD_REQUEST,
    413: CloseCode.MESSAGE_TOO_BIG,
    415: CloseCode.UNSUPPORTED_DATA,
    421: CloseCode.MISDIRECTED,
    422: CloseCode.BAD_REQUEST,
    429: CloseCode.TRY_AGAIN_LATER,
    502: CloseCode.TRY_AGAIN_LATER,
    503: CloseCode.TRY_AGAIN_LATER,
    504: CloseCode.TRY_AGAIN_LATER,
}
# The refusals a door makes before any route: no valid token, another site's page or not the
# caller's, a Host that is not this server's name.
HANDSHAKE_REFUSALS = frozenset({401, 403, 421})
MAX_REASON_BYTES = (
    120  # a close frame's reason must fit in 123 bytes (RFC 6455: 125 of payload, 2 for the code)
)


def close_reason(text: str) -> str:
    """A close reason that fits a close frame, cut at a character boundary."""
    return text.encode("utf-8")[:MAX_REASON_BYTES].decode("utf-8", "ignore")


async def refuse_socket(send: Callable[[dict[str, Any]], Awaitable[None]], code: int, reason: str) -> None:
    """Close an ASGI WebSocket with ``code`` and ``reason`` (cut to fit): the one way a door of the
    app refuses one. Before the handshake, the app's outermost middleware
    (api/middleware/socket_refusal.py) accepts it first, so the client sees the code and reason."""
    await send({"type": "websocket.close", "code": code, "reason": close_reason(reason)})
