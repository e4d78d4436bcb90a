"""viser's own client page, served by the app with our key script injected, and the WebSocket
proxy that carries it to the viser server on loopback: one port for everything."""

from __future__ import annotations

import logging
from functools import cache
from pathlib import Path
from typing import Any

import viser
import websockets
from fastapi import APIRouter, Request, WebSocket, status
from fastapi.responses import FileResponse, HTMLResponse, RedirectResponse, Response
from starlette.requests import HTTPConnection

from api.deps import classroom_of, keep_token_and_go, lab_of, token_of
from api.websockets.relay import relay
from server.base.access import token_matches
from server.base.close_codes import CloseCode
from server.classroom import ClassroomError
from server.peripherals.viewer.views import PageViews, ViewRegistry
from server.peripherals.viewer.viser_guard import PROXY_TOKEN_HEADER

log = logging.getLogger(__name__)
router = APIRouter(include_in_schema=False)
VISER_INDEX = Path(viser.__file__).parent / "client" / "build" / "index.html"
INJECT_STYLES = ("page.css",)
# The page's bundle (web/src/lab, built into static/build at set-up): a classic script in <head>,
# so its key capture is in place before viser's scripts run and see keys.
INJECT_SCRIPTS = ("build/lab.js",)
INJECT = "".join(f'<link rel="stylesheet" href="/static/{name}">' for name in INJECT_STYLES) + "".join(
    f'<script src="/static/{name}"></script>' for name in INJECT_SCRIPTS
)
# The browser's tab says which page this is (viser's says "Viser"), as the tools page's does.
VISER_TITLE, LAB_TITLE = "<title>Viser</title>", "<title>Teleop lab · ROS 2 Lab 2</title>"
PROXY_MAX_FRAME_BYTES = 1 << 20  # browser → viser: camera moves and GUI clicks, all small
# Cross-origin isolation, so the page may share memory with its pose worker (web/src/lab/poses.ts):
# everything the page loads comes from this origin, and it opens other pages only as new tabs.
ISOLATED = {"Cross-Origin-Opener-Policy": "same-origin", "Cross-Origin-Embedder-Policy": "require-corp"}
STATIC = Path(__file__).resolve().parents[2] / "static"
POSES_WORKER = STATIC / "build" / "poses.worker.js"


@cache
def viser_html() -> str:
    return VISER_INDEX.read_text(encoding="utf-8")


@cache
def index_html() -> str:
    html = viser_html()
    if "</head>" not in html or VISER_TITLE not in html:
        raise RuntimeError(f"viser's page at {VISER_INDEX} changed shape; pin viser==1.1.1")
    if not all((STATIC / name).is_file() for name in INJECT_SCRIPTS):
        log.warning("the page's scripts are not built (static/build): run scripts/run.sh, which builds them")
    return html.replace(VISER_TITLE, LAB_TITLE, 1).replace("</head>", INJECT + "</head>", 1)


@router.get("/", response_class=HTMLResponse)
async def index(request: Request) -> Response:
    classroom = classroom_of(request)
    if classroom is not None:  # a class server: the join form until this browser has a world
        grant = classroom.grant(token_of(request))
        if grant is None:
            return FileResponse(STATIC / "join.html", headers={"Cache-Control": "no-cache"})
        if grant.is_instructor:
            return RedirectResponse("/instructor", status.HTTP_303_SEE_OTHER)
    elif (lab_token := request.app.state.settings.listen.token) is not None:  # one lab behind --token
        asked = request.query_params.get("token")
        if asked is not None:  # the printed link: keep the token in a cookie, not the address bar
            if not token_matches(asked, lab_token):
                return Response("that link's token is not this lab's", status.HTTP_403_FORBIDDEN)
            return keep_token_and_go("/", asked)
        if not token_matches(token_of(request), lab_token):
            return Response(
                "this lab needs its token: open the link the server printed (/?token=...)",
                status.HTTP_401_UNAUTHORIZED,
            )
    return HTMLResponse(index_html(), headers={"Cache-Control": "no-cache", **ISOLATED})


@router.get("/instructor", response_class=HTMLResponse)
async def instructor(request: Request, token: str | None = None) -> Response:
    """The instructor's page. Opened once with ``?token=`` (the link the class server prints),
    it keeps the token in an HTTP-only cookie and drops it from the address bar."""
    classroom = classroom_of(request)
    if classroom is None:
        return Response("not a class server (start it with --classroom)", status.HTTP_404_NOT_FOUND)
    if token is not None:
        grant = classroom.grant(token)
        if grant is None or not grant.is_instructor:
            return Response("that link's token is not the instructor's", status.HTTP_403_FORBIDDEN)
        return keep_token_and_go("/instructor", token)
    grant = classroom.grant(token_of(request))
    if grant is None or not grant.is_instructor:
        return Response("open the instructor's link the class server printed", status.HTTP_401_UNAUTHORIZED)
    return FileResponse(STATIC / "instructor.html", headers={"Cache-Control": "no-cache"})


def _display_of(conn: HTTPConnection) -> Any:
    """The 3D view of the lab (or the caller's world on a class server); None if there is none."""
    try:
        return lab_of(conn).display
    except ClassroomError:
        return None


@router.get("/page/poses.worker.js", response_class=Response)
async def poses_worker() -> Response:
    """The pose stream's worker, with the isolation its page has (a dedicated worker needs its own)."""
    if not POSES_WORKER.is_file():
        return Response("the page's scripts are not built: run scripts/run.sh", status.HTTP_404_NOT_FOUND)
    return Response(POSES_WORKER.read_bytes(), media_type="text/javascript", headers=ISOLATED)


@router.get("/page/views")
async def views(request: Request) -> PageViews:
    """The labs' camera views for the page, and the one a page with no remembered choice opens on."""
    display = _display_of(request)
    if display is None:
        return {"views": [], "suggested": None}
    views: ViewRegistry = display.views
    return views.to_json()


@router.websocket("/")
async def viser_proxy(websocket: WebSocket) -> None:
    await _proxy_to(_display_of(websocket), websocket)


def _instructors_view(conn: HTTPConnection) -> tuple[Any, Response | None]:
    """The class view (every world's drone) for the instructor; else why not, as a response."""
    classroom = classroom_of(conn)
    if classroom is None:
        return None, Response("not a class server (start it with --classroom)", status.HTTP_404_NOT_FOUND)
    grant = classroom.grant(token_of(conn))
    if grant is None or not grant.is_instructor:
        return None, Response(
            "open the instructor's link the class server printed", status.HTTP_401_UNAUTHORIZED
        )
    return classroom.view, None  # None: no view (a world worker has none)


@router.get("/instructor/view", response_class=HTMLResponse)
async def instructor_view(request: Request) -> Response:
    """viser's own page for the class view, shown in a frame of the instructor's page (no key script:
    nothing here flies a drone)."""
    view, refused = _instructors_view(request)
    if refused is not None:
        return refused
    if view is None:
        return Response("the 3D view is off (--no-viewer)", status.HTTP_404_NOT_FOUND)
    # Framed by the instructor's page only, never by another site's.
    headers = {
        "Cache-Control": "no-cache",
        "Content-Security-Policy": "frame-ancestors 'self'",
        "X-Frame-Options": "SAMEORIGIN",
    }
    return HTMLResponse(viser_html(), headers=headers)


@router.websocket("/instructor/view")
async def instructor_view_proxy(websocket: WebSocket) -> None:
    view, refused = _instructors_view(websocket)
    if refused is not None:
        if refused.status_code == status.HTTP_401_UNAUTHORIZED:
            await websocket.close(CloseCode.UNAUTHORIZED, "the instructor's token is needed")
        else:
            await websocket.close(CloseCode.NOT_FOUND, "not a class server")
        return
    await _proxy_to(view.display if view is not None else None, websocket)


async def _proxy_to(display: Any, websocket: WebSocket) -> None:
    """Carry ``websocket`` to ``display``'s viser server (on loopback, behind its proxy token)."""
    if display is None:
        await websocket.close(status.WS_1013_TRY_AGAIN_LATER, "the 3D view is not running")
        return
    subprotocols = websocket.scope.get("subprotocols") or None
    try:
        upstream = await websockets.connect(
            f"ws://127.0.0.1:{display.port}",
            subprotocols=subprotocols,
            additional_headers={PROXY_TOKEN_HEADER: display.proxy_token},
            max_size=None,
            compression=None,
        )
    except (OSError, TimeoutError, ValueError, websockets.exceptions.WebSocketException) as exc:
        # viser refuses a client without its subprotocol (HTTP 400): refuse the browser in turn.
        await websocket.close(
            status.WS_1008_POLICY_VIOLATION, f"the 3D view refused the connection: {exc}"[:120]
        )
        return
    await relay(websocket, upstream, PROXY_MAX_FRAME_BYTES)
