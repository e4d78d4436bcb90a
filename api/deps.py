"""What route handlers take from the running app: the lab a call acts on.

One lab, or on a class server (``--classroom``) the world the caller's token names: a student's
own world, or for the instructor the world named by ``X-Lab-World`` (or ``?world=``). No valid
token is 401, another student's world 403; a student's writes are rate-limited per world (429):
the classroom's refusals (server/classroom/errors.py), which api/errors.py answers.
"""

from __future__ import annotations

from typing import Annotated, cast

from fastapi import Depends, Request, Response, WebSocket, WebSocketException, status
from fastapi.responses import RedirectResponse
from starlette.requests import HTTPConnection

from api.errors import close_reason, refusal_close_code
from server.base.access import bearer_token, token_matches
from server.classroom import Classroom, ClassroomError, Grant
from server.classroom.errors import NotAuthenticatedError, WorldElsewhereError
from server.world.lab import Lab

TOKEN_COOKIE = "lab_token"
COOKIE_MAX_AGE_S = 12 * 3600  # a school day
WORLD_HEADER = "x-lab-world"
SAFE_METHODS = frozenset({"GET", "HEAD", "OPTIONS"})


def classroom_of(conn: HTTPConnection) -> Classroom | None:
    return getattr(conn.app.state, "classroom", None)


def token_of(conn: HTTPConnection) -> str | None:
    """A bearer token (REST, WebSockets, the CLI), the page's HTTP-only cookie, or for a WebSocket
    ``?token=`` (clients such as Foxglove's cannot add a header)."""
    bearer = bearer_token(conn.headers.get("authorization"))
    if bearer is not None:
        return bearer
    cookie = conn.cookies.get(TOKEN_COOKIE)
    if cookie is None and conn.scope["type"] == "websocket":
        return conn.query_params.get("token")
    return cookie


def grant_of(conn: HTTPConnection, classroom: Classroom) -> Grant:
    grant = classroom.grant(token_of(conn))
    if grant is None:
        raise NotAuthenticatedError(
            "join the class first: no valid token (lab_token cookie or Authorization: Bearer)"
        )
    return grant


def lab_of(conn: HTTPConnection) -> Lab:
    """The lab this call acts on; ClassroomError says why a class server refuses it."""
    classroom = classroom_of(conn)
    if classroom is None:
        lab = cast(Lab, conn.app.state.lab)
        lab_token = lab.settings.listen.token
        if lab_token is not None and not token_matches(token_of(conn), lab_token):
            raise NotAuthenticatedError(
                "this lab needs its token: open the link the server printed "
                "(/?token=...), or send Authorization: Bearer"
            )
        return lab
    grant = grant_of(conn, classroom)
    asked = conn.headers.get(WORLD_HEADER) or conn.query_params.get("world")
    world = classroom.world_for(grant, asked)
    if world.lab is None:  # api/middleware/world_proxy.py passes on what acts on a worker's world
        where = world.worker.id if world.worker is not None else "another process"
        raise WorldElsewhereError(f"world {world.name!r} runs on world worker {where!r}: nothing here for it")
    writing = conn.scope["type"] == "http" and conn.scope["method"] not in SAFE_METHODS
    if writing and not grant.is_instructor:
        classroom.charge_write(world)  # a world worker charges none: its class server did
    return world.lab


async def _lab_dep(request: Request) -> Lab:
    """LabDep: ``lab_of`` on the loop, as the handlers run (a refusal is a ClassroomError, which
    api/errors.py answers with its status). FastAPI runs a plain ``def`` dependency in its thread
    pool: every call then went to a thread and came back, two more turns of a loop that a class's
    worlds keep busy, and it read the classroom's state off the loop."""
    return lab_of(request)


def set_token_cookie(response: Response, token: str) -> None:
    """HTTP-only (no script reads it), same-site (no other site's page sends it)."""
    response.set_cookie(
        TOKEN_COOKIE, token, max_age=COOKIE_MAX_AGE_S, httponly=True, samesite="strict", path="/"
    )


def keep_token_and_go(path: str, token: str) -> Response:
    """A link that carried ``?token=``: keep the token in the cookie and drop it from the address bar."""
    response = RedirectResponse(path, status.HTTP_303_SEE_OTHER)
    set_token_cookie(response, token)
    return response


async def _ws_lab(websocket: WebSocket) -> Lab:
    try:
        return lab_of(websocket)
    except ClassroomError as exc:
        raise WebSocketException(refusal_close_code(exc), close_reason(str(exc))) from None


LabDep = Annotated[Lab, Depends(_lab_dep)]
WsLabDep = Annotated[Lab, Depends(_ws_lab)]
