"""The one place where errors become HTTP statuses and WebSocket close codes.

The bus's, the messages', the launcher's, the classroom's and the app's own error types are
registered as exception handlers here, so route handlers only call the lab and never catch.
Anything else is a bug: ``ErrorMiddleware`` answers it with a 500 (or closes a WebSocket with
1011) carrying a request id, logs it with its traceback under that id, and never sends its text
to the client.
"""

from __future__ import annotations

import logging
import math
import uuid
from collections.abc import Awaitable, Callable

from fastapi import FastAPI, Request, status
from fastapi.exceptions import RequestValidationError
from starlette.exceptions import HTTPException as StarletteHTTPException
from starlette.responses import Response
from starlette.routing import Match
from starlette.types import ASGIApp, Message, Receive, Scope, Send

from api.protocol.json_codec import SafeJSONResponse
from node_runtime.ament.index import ExecutableNotFoundError, PackageNotFoundError, WorkspaceError
from node_runtime.bus import (
    DestroyedError,
    InvalidNameError,
    InvalidQoSError,
    ServiceTimeoutError,
    TopicTypeError,
    UnknownNodeError,
    UnknownServiceError,
    UnknownTopicError,
)
from node_runtime.limits import LimitExceededError, ValueLimitError
from node_runtime.msgs import MessageError, UnknownTypeError
from server.base.close_codes import CLOSE_FOR_STATUS, HANDSHAKE_REFUSALS, refuse_socket
from server.base.close_codes import CloseCode as CloseCode  # where the routes import it from
from server.base.close_codes import close_reason as close_reason  # likewise
from server.classroom.errors import (
    AddressLimitError,
    AtCapacityError,
    BadHandoverError,
    BadNameError,
    ClassFullError,
    ClassroomError,
    JoinLapsedError,
    JoinThroughClassServerError,
    NameTakenError,
    NoRoomError,
    NoSavedProgressError,
    NotAuthenticatedError,
    NotHereError,
    NotYoursError,
    ProgressOwnedError,
    RateLimitedError,
    StudentCodeElsewhereError,
    UnknownTicketError,
    UnknownWorldError,
    WorkerFailedError,
    WorkerRefusedError,
    WorkerTimeoutError,
    WorldElsewhereError,
    WorldJoinedError,
    WorldNotNamedError,
    WrongCodeError,
)
from server.host.processes.sandbox import StudentCodeRefusedError
from server.packages.launch_files import LaunchFileNotFoundError
from server.peripherals.bag.errors import (
    BagBusyError,
    BagError,
    BagExistsError,
    BagLimitError,
    BagNotFoundError,
)
from server.services.api_node.publishers import PublisherError, UnknownPublisherError
from server.services.launch.description import LaunchFileError
from server.services.launch.groups import UnknownLaunchError
from server.services.workspace.errors import (
    BadArchiveError,
    BadPackageError,
    BadPathError,
    ChangedError,
    FileMissingError,
    NotTextError,
    NoWorkspaceError,
    TakenError,
    TooLargeError,
)
from server.world.checkpoints.progress import (
    NotPngError,
    UnknownCheckpointError,
    UnknownQuestionError,
)
from server.world.checkpoints.progress import TooLargeError as AnswerTooLargeError

log = logging.getLogger("api.errors")


class BodyTooLarge(StarletteHTTPException):
    """Raised while a body without Content-Length is read; an HTTPException so that FastAPI's
    body parser re-raises it (any other exception there becomes a 400 "error parsing the body")."""

    def __init__(self, limit: int) -> None:
        self.limit = limit
        super().__init__(413, f"body larger than {limit} bytes")

    def __str__(self) -> str:
        return str(self.detail)


# Checked in order, so a subclass must come before its base. Nothing broader than these.
ERROR_STATUS: tuple[tuple[type[Exception], int], ...] = (
    (UnknownTopicError, status.HTTP_404_NOT_FOUND),
    (UnknownNodeError, status.HTTP_404_NOT_FOUND),
    (UnknownServiceError, status.HTTP_404_NOT_FOUND),
    (UnknownPublisherError, status.HTTP_404_NOT_FOUND),
    (UnknownLaunchError, status.HTTP_404_NOT_FOUND),
    (PackageNotFoundError, status.HTTP_404_NOT_FOUND),
    (LaunchFileNotFoundError, status.HTTP_404_NOT_FOUND),
    (ExecutableNotFoundError, status.HTTP_404_NOT_FOUND),
    (TopicTypeError, status.HTTP_409_CONFLICT),
    (DestroyedError, status.HTTP_409_CONFLICT),
    (LimitExceededError, status.HTTP_429_TOO_MANY_REQUESTS),
    (ServiceTimeoutError, status.HTTP_504_GATEWAY_TIMEOUT),
    (StudentCodeElsewhereError, status.HTTP_409_CONFLICT),  # a world worker away from the class's router
    (StudentCodeRefusedError, status.HTTP_503_SERVICE_UNAVAILABLE),  # no sandbox on a shared server
    (BodyTooLarge, status.HTTP_413_CONTENT_TOO_LARGE),
    (AnswerTooLargeError, status.HTTP_413_CONTENT_TOO_LARGE),
    (UnknownQuestionError, status.HTTP_404_NOT_FOUND),
    (UnknownCheckpointError, status.HTTP_404_NOT_FOUND),
    (NotPngError, status.HTTP_422_UNPROCESSABLE_CONTENT),
    (InvalidNameError, status.HTTP_422_UNPROCESSABLE_CONTENT),
    (InvalidQoSError, status.HTTP_422_UNPROCESSABLE_CONTENT),
    (MessageError, status.HTTP_422_UNPROCESSABLE_CONTENT),
    (UnknownTypeError, status.HTTP_422_UNPROCESSABLE_CONTENT),
    (LaunchFileError, status.HTTP_422_UNPROCESSABLE_CONTENT),
    (
        WorkspaceError,
        status.HTTP_422_UNPROCESSABLE_CONTENT,
    ),  # a student's package.xml, setup.py, duplicate name
    (ValueLimitError, status.HTTP_422_UNPROCESSABLE_CONTENT),
    (PublisherError, status.HTTP_422_UNPROCESSABLE_CONTENT),
    (BagNotFoundError, status.HTTP_404_NOT_FOUND),
    (BagExistsError, status.HTTP_409_CONFLICT),
    (BagBusyError, status.HTTP_409_CONFLICT),
    (BagLimitError, status.HTTP_429_TOO_MANY_REQUESTS),
    (BagError, status.HTTP_422_UNPROCESSABLE_CONTENT),
    (NoWorkspaceError, status.HTTP_404_NOT_FOUND),
    (FileMissingError, status.HTTP_404_NOT_FOUND),
    (BadPathError, status.HTTP_422_UNPROCESSABLE_CONTENT),
    (BadPackageError, status.HTTP_422_UNPROCESSABLE_CONTENT),
    (BadArchiveError, status.HTTP_422_UNPROCESSABLE_CONTENT),
    (TakenError, status.HTTP_409_CONFLICT),
    (ChangedError, status.HTTP_412_PRECONDITION_FAILED),
    (TooLargeError, status.HTTP_413_CONTENT_TOO_LARGE),
    (NotTextError, status.HTTP_415_UNSUPPORTED_MEDIA_TYPE),
    # The classroom's refusals (server/classroom/errors.py), with Retry-After when one says when.
    (NotAuthenticatedError, status.HTTP_401_UNAUTHORIZED),
    (WorldNotNamedError, status.HTTP_400_BAD_REQUEST),
    (NotYoursError, status.HTTP_403_FORBIDDEN),
    (WrongCodeError, status.HTTP_403_FORBIDDEN),
    (JoinThroughClassServerError, status.HTTP_403_FORBIDDEN),
    (NotHereError, status.HTTP_404_NOT_FOUND),
    (WorldElsewhereError, status.HTTP_404_NOT_FOUND),
    (UnknownWorldError, status.HTTP_404_NOT_FOUND),
    (UnknownTicketError, status.HTTP_404_NOT_FOUND),
    (NoSavedProgressError, status.HTTP_404_NOT_FOUND),
    (NameTakenError, status.HTTP_409_CONFLICT),
    (ProgressOwnedError, status.HTTP_409_CONFLICT),
    (WorldJoinedError, status.HTTP_409_CONFLICT),
    (BadNameError, status.HTTP_422_UNPROCESSABLE_CONTENT),
    (BadHandoverError, status.HTTP_422_UNPROCESSABLE_CONTENT),
    (ClassFullError, status.HTTP_429_TOO_MANY_REQUESTS),
    (AddressLimitError, status.HTTP_429_TOO_MANY_REQUESTS),
    (RateLimitedError, status.HTTP_429_TOO_MANY_REQUESTS),
    (AtCapacityError, status.HTTP_503_SERVICE_UNAVAILABLE),
    (JoinLapsedError, status.HTTP_503_SERVICE_UNAVAILABLE),
    (NoRoomError, status.HTTP_503_SERVICE_UNAVAILABLE),
    (WorkerFailedError, status.HTTP_502_BAD_GATEWAY),
    (WorkerTimeoutError, status.HTTP_504_GATEWAY_TIMEOUT),
    (WorkerRefusedError, status.HTTP_502_BAD_GATEWAY),  # a client error of the worker's: passed on
)


def status_for(exc: BaseException) -> int | None:
    """The HTTP status of a known error type, or None for a bug. A world worker's refusal of what
    the class server passed on keeps the worker's status when it is the caller's fault (4xx)."""
    answered = exc.answered if isinstance(exc, WorkerRefusedError) else None
    if answered is not None and answered < status.HTTP_500_INTERNAL_SERVER_ERROR:
        return answered
    return next((code for kind, code in ERROR_STATUS if isinstance(exc, kind)), None)


def close_code(exc: BaseException) -> CloseCode | None:
    """The WebSocket close code of a known error type, or None for a bug."""
    code = status_for(exc)
    return None if code is None else CLOSE_FOR_STATUS[code]


def refusal_close_code(exc: ClassroomError) -> CloseCode:
    """The close code of a classroom refusal at a WebSocket's door: no valid token and not the
    caller's as the handshake's own refusals close; any other (no world named, none of that name,
    one that runs on a world worker) a policy violation (1008)."""
    code = status_for(exc)
    return CLOSE_FOR_STATUS[code] if code in HANDSHAKE_REFUSALS else CloseCode.POLICY_VIOLATION


def _handler(code: int) -> Callable[[Request, Exception], Awaitable[SafeJSONResponse]]:
    async def handle(_request: Request, exc: Exception) -> SafeJSONResponse:
        return SafeJSONResponse({"detail": str(exc)}, status_code=code)

    return handle


async def _validation_error(_request: Request, exc: Exception) -> SafeJSONResponse:
    """FastAPI's 422, without echoing the input back (it may be huge, or not JSON-serialisable)."""
    errors = exc.errors() if isinstance(exc, RequestValidationError) else []
    detail = [{"type": e.get("type"), "loc": list(e.get("loc", ())), "msg": e.get("msg")} for e in errors]
    return SafeJSONResponse({"detail": detail}, status_code=status.HTTP_422_UNPROCESSABLE_CONTENT)


_METHODS = ("GET", "HEAD", "POST", "PUT", "PATCH", "DELETE", "OPTIONS")


def _allowed_methods(request: Request) -> list[str]:
    """Every method some route answers at this path (Starlette's 405 names only the first route's)."""
    routes = request.app.router.routes
    return [
        method
        for method in _METHODS
        if any(route.matches({**request.scope, "method": method})[0] is Match.FULL for route in routes)
    ]


async def _http_error(request: Request, exc: Exception) -> Response:
    """Starlette's own errors (404 for no route, 405 ...), with an ``Allow`` that lists every method."""
    assert isinstance(exc, StarletteHTTPException)
    headers = dict(exc.headers or {})
    if exc.status_code == status.HTTP_405_METHOD_NOT_ALLOWED:
        headers["Allow"] = ", ".join(_allowed_methods(request))
    return SafeJSONResponse({"detail": exc.detail}, status_code=exc.status_code, headers=headers)


def register_error_handlers(app: FastAPI) -> None:
    """Every known error type's status, and FastAPI's validation errors; bugs are ``ErrorMiddleware``'s."""
    for kind, code in ERROR_STATUS:
        app.add_exception_handler(
            kind, _classroom_error if issubclass(kind, ClassroomError) else _handler(code)
        )
    app.add_exception_handler(RequestValidationError, _validation_error)
    app.add_exception_handler(StarletteHTTPException, _http_error)
    app.add_exception_handler(ChangedError, _changed_error)


async def _changed_error(_request: Request, exc: Exception) -> SafeJSONResponse:
    """A stale save: the detail, and the file's version now (null: it is gone), so the page can offer
    the choice."""
    etag = exc.etag if isinstance(exc, ChangedError) else None
    return SafeJSONResponse(
        {"detail": str(exc), "etag": etag}, status_code=status.HTTP_412_PRECONDITION_FAILED
    )


async def _classroom_error(_request: Request, exc: Exception) -> SafeJSONResponse:
    """A classroom refusal: its status, and ``Retry-After`` when it says when to try again."""
    code = status_for(exc) or status.HTTP_500_INTERNAL_SERVER_ERROR
    after = exc.retry_after_s if isinstance(exc, ClassroomError) else None
    headers = {"Retry-After": str(max(1, math.ceil(after)))} if after is not None else None
    return SafeJSONResponse({"detail": str(exc)}, status_code=code, headers=headers)


class ErrorMiddleware:
    """The last resort for bugs: a 500 or a 1011 close with a request id; the traceback goes to
    the log under the same id, never to the client."""

    def __init__(self, app: ASGIApp) -> None:
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] not in ("http", "websocket"):
            return await self.app(scope, receive, send)
        started = False

        async def tracking_send(message: Message) -> None:
            nonlocal started
            if message["type"] in ("http.response.start", "websocket.accept", "websocket.close"):
                started = True
            await send(message)

        try:
            await self.app(scope, receive, tracking_send)
        except Exception:
            request_id = uuid.uuid4().hex[:12]
            log.exception(
                "unexpected error in %s %s (request id %s)", scope["type"], scope["path"], request_id
            )
            await _answer_bug(scope, send, request_id, started)


async def _answer_bug(scope: Scope, send: Send, request_id: str, started: bool) -> None:
    detail = f"internal error (request id {request_id})"
    if scope["type"] == "websocket":
        # Before the handshake this refuses it; after, it closes with 1011. Either way, a code.
        try:
            await refuse_socket(send, CloseCode.INTERNAL_ERROR, detail)
        except (RuntimeError, OSError):  # the socket is already gone
            return
        return
    if started:
        return  # the response is half sent; the server drops the connection
    response = SafeJSONResponse({"detail": detail, "request_id": request_id}, status_code=500)
    await response({"type": "http"}, _never_receive, send)


async def _never_receive() -> Message:
    return {"type": "http.disconnect"}
