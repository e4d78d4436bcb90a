"""A cap on a student's WebSockets, whatever the route: keys, topic echoes, rosbridge, the 3D
view, and those passed on to a world worker. Each is charged to the world its token names while
it is open; one over ``world_sockets`` is accepted and closed at once with 1013 (try again later)
and a reason that names the limit, so the student's other sockets (and other worlds) keep their
share. The instructor's sockets are not capped, and nothing is charged on a lab without a class.
"""

from __future__ import annotations

from starlette.requests import HTTPConnection
from starlette.types import ASGIApp, Receive, Scope, Send

from api.deps import WORLD_HEADER, token_of
from api.errors import CloseCode
from server.base.close_codes import refuse_socket
from server.classroom import Classroom, ClassroomError, World


def charged_world(classroom: Classroom, scope: Scope) -> World | None:
    """The world a student's socket counts against; None for the instructor or a socket the
    route itself refuses (no valid token, another world)."""
    conn = HTTPConnection(scope)
    grant = classroom.grant(token_of(conn))
    if grant is None or grant.is_instructor:
        return None
    try:
        return classroom.world_for(grant, conn.headers.get(WORLD_HEADER) or conn.query_params.get("world"))
    except ClassroomError:
        return None


class SocketCapMiddleware:
    def __init__(self, app: ASGIApp) -> None:
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        classroom: Classroom | None = None
        if scope["type"] == "websocket":
            classroom = getattr(scope["app"].state, "classroom", None)
        world = charged_world(classroom, scope) if classroom is not None else None
        if world is None:
            await self.app(scope, receive, send)
            return
        assert classroom is not None
        cap = classroom.class_settings.world.sockets
        if world.sockets >= cap:
            await _refuse(send, f"at most {cap} WebSockets open for world {world.name!r}; close one first")
            return
        world.sockets += 1
        try:
            await self.app(scope, receive, send)
        finally:
            world.sockets -= 1


async def _refuse(send: Send, reason: str) -> None:
    """Close with 1013: the app's outermost middleware accepts first, so a browser sees the code
    and reason (a refused handshake would only show it an HTTP error)."""
    await refuse_socket(send, CloseCode.TRY_AGAIN_LATER, reason)
