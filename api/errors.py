"""One place that maps the bus's and the messages' errors to HTTP statuses and WebSocket close codes."""

from __future__ import annotations

from enum import IntEnum

from fastapi import HTTPException, status

from server.bus import (
    BusError,
    DestroyedError,
    InvalidNameError,
    InvalidQoSError,
    ServiceTimeoutError,
    TopicTypeError,
    UnknownNodeError,
    UnknownServiceError,
    UnknownTopicError,
)  # fmt: skip
from server.msgs import MessageError, UnknownTypeError


class CloseCode(IntEnum):
    """WebSocket close codes this API uses (RFC 6455 names; 4xxx are the app's own)."""

    NORMAL = 1000
    GOING_AWAY = 1001
    UNSUPPORTED_DATA = 1003
    INVALID_PAYLOAD = 1007
    POLICY_VIOLATION = 1008
    MESSAGE_TOO_BIG = 1009
    INTERNAL_ERROR = 1011
    TRY_AGAIN_LATER = 1013
    BAD_REQUEST = 4400
    UNKNOWN_TOPIC = 4404
    TYPE_CONFLICT = 4409


def http_error(exc: Exception) -> HTTPException:
    """The HTTP error for an exception from the bus or the message layer."""
    if isinstance(exc, (UnknownTopicError, UnknownNodeError, UnknownServiceError)):
        return HTTPException(status.HTTP_404_NOT_FOUND, str(exc))
    if isinstance(exc, ServiceTimeoutError):
        return HTTPException(status.HTTP_504_GATEWAY_TIMEOUT, str(exc))
    if isinstance(exc, TopicTypeError):
        return HTTPException(status.HTTP_409_CONFLICT, str(exc))
    if isinstance(exc, (InvalidNameError, InvalidQoSError, MessageError, UnknownTypeError, ValueError)):
        return HTTPException(status.HTTP_422_UNPROCESSABLE_CONTENT, str(exc))
    if isinstance(exc, (DestroyedError, BusError)):
        return HTTPException(status.HTTP_409_CONFLICT, str(exc))
    return HTTPException(status.HTTP_500_INTERNAL_SERVER_ERROR, f"{type(exc).__name__}: {exc}")


def close_code(exc: Exception) -> CloseCode:
    if isinstance(exc, UnknownTopicError):
        return CloseCode.UNKNOWN_TOPIC
    if isinstance(exc, TopicTypeError):
        return CloseCode.TYPE_CONFLICT
    return CloseCode.BAD_REQUEST
