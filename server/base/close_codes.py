"""The WebSocket close codes the app uses: RFC 6455's, and the app's own 4xxx, each 4000 plus the
HTTP status a request refused for the same reason gets."""

from __future__ import annotations

from enum import IntEnum


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


# A refused handshake's close code (api/middleware/socket_refusal.py, the bridges' fronts), by the status a request would get.
REFUSAL_FOR_STATUS = {401: CloseCode.UNAUTHORIZED, 403: CloseCode.FORBIDDEN, 421: CloseCode.MISDIRECTED}
