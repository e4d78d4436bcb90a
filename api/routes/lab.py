"""REST: health and the lab's own controls (reset the rocket)."""

from __future__ import annotations

import math
import time

from fastapi import APIRouter, HTTPException, Query, Request, status

from api.deps import WORLD_HEADER, LabDep, classroom_of, grant_of, lab_of, token_of
from api.protocol.responses import responses
from api.protocol.schemas import Health, Status, WorkspaceInfo, ZenohJoin, ZenohStatus
from node_runtime.transport.acl import Credentials
from server.classroom import Classroom
from server.host.processes.command import graph_overrides
from server.host.processes.start_pacing import TICKET_CHARS, StartPacer
from server.host.settings import Settings

# Handlers are ``async def`` on purpose: the bus belongs to the event loop, and a plain ``def``
# handler would run in a worker thread and race the executor (timer heap, wake-up future).
router = APIRouter(prefix="/api", tags=["lab"], responses=responses())


STARTED_AT = time.monotonic()


@router.get("/health", openapi_extra={"security": []})
async def health(request: Request) -> Health:
    """The lab's; on a class server without a token, the whole server's (every world summed), so a
    health check needs no secret; with a token, the caller's world. No token is needed."""
    classroom = classroom_of(request)
    if classroom is not None and token_of(request) is None:
        labs = [w.lab for w in classroom.worlds.values() if w.lab is not None]
        return Health(
            status="ok",
            launch=classroom.settings.lab.launch,
            nodes=sum(len(lab.bus.nodes) for lab in labs),
            topics=sum(len(lab.bus.topics) for lab in labs),
            uptime_s=round(time.monotonic() - STARTED_AT, 3),
        )
    # One lab answers without its token too: counts and uptime are not worth one, and a
    # container's health check has none.
    lab = lab_of(request) if classroom is not None else request.app.state.lab
    return Health(
        status="ok",
        launch=lab.settings.lab.launch,
        nodes=len(lab.bus.nodes),
        topics=len(lab.bus.topics),
        uptime_s=round(time.monotonic() - lab.started_at, 3),
        zenoh=ZenohStatus.model_validate(lab.zenoh.status()) if lab.zenoh is not None else None,
        zenoh_error=lab.zenoh_error,
    )


@router.get("/zenoh/join", responses=responses(404, 429))
async def zenoh_join(
    request: Request,
    start: bool = False,
    turn: str | None = Query(
        None,
        max_length=TICKET_CHARS,
        description="new: keep this start's turn if it must wait; then the ticket a 429 gave (Start-Turn)",
    ),
) -> ZenohJoin:
    """Where and how a node process joins this lab's ROS graph on Zenoh: the router, the ROS domain
    and, on a class server, the world's own login (its router lets each world's user into that
    world's domain only). ``env`` is ready to export, for ``ros2lab run`` or a ROS 2 node on rmw_zenoh.
    The instructor naming no world gets the class's own graph, where every world's topics show
    under its name (``/ada/uav/sensors/gps``). ``start=true`` (as ``ros2lab run`` asks) is a node
    process about to start: such joins are paced (server/host/processes/start_pacing.py), with too
    many starting at once 429: ``Retry-After`` (whole seconds), ``Retry-After-Ms`` (the wait to the
    millisecond) and, for a start that asked with ``turn=new``, ``Start-Turn``: the ticket that
    keeps its turn, to ask again with as ``turn``; after the request's own checks."""
    classroom = classroom_of(request)
    named = request.headers.get(WORLD_HEADER) or request.query_params.get("world")
    if classroom is not None and not named and grant_of(request, classroom).is_instructor:
        return _paced(classroom.start_pacer, start, turn, "", _class_graph_join(classroom))
    lab = lab_of(request)
    link = lab.zenoh
    if link is None:
        why = (
            f"its Zenoh session did not open: {lab.zenoh_error}"
            if lab.zenoh_error
            else "started with --no-zenoh"
        )
        raise HTTPException(status.HTTP_404_NOT_FOUND, f"this lab's graph is not on Zenoh ({why})")
    join = _join(link.router_endpoint(), link.settings.domain_id, link.settings.login, _nice(lab.settings))
    return _paced(lab.start_pacer, start, turn, lab.bus.label or "", join)


def _nice(settings: Settings) -> int | None:
    """Where the server serves others (a class, a lab beyond loopback), students' node processes
    run below its worlds: the niceness its sandbox gives them (node_runtime/process/priority.py). A
    lab on loopback serves its user alone, whose nodes run as they were started."""
    return settings.sandbox.nice if settings.confines_paths else None


def retry_after(wait_s: float) -> str:
    """``Retry-After`` in whole seconds, as HTTP writes it (at least 1)."""
    return str(max(1, math.ceil(wait_s)))


def _paced(pacer: StartPacer | None, start: bool, ticket: str | None, who: str, join: ZenohJoin) -> ZenohJoin:
    """The join, or 429 with the time of its turn and the ticket that keeps it when it is a start
    the server's pacer defers (server/host/processes/start_pacing.py); ``who``: the world asking."""
    turn = pacer.admit(ticket, who) if start and pacer is not None else None
    if turn is not None:
        headers = {
            "Retry-After": retry_after(turn.wait_s),
            "Retry-After-Ms": str(math.ceil(turn.wait_s * 1000)),
        }
        if turn.ticket is not None:
            headers["Start-Turn"] = turn.ticket
        raise HTTPException(
            status.HTTP_429_TOO_MANY_REQUESTS,
            f"too many node processes starting at once on this server; ask again in {turn.wait_s:.1f} s",
            headers=headers,
        )
    return join


def _class_graph_join(classroom: Classroom) -> ZenohJoin:
    router = classroom.router_endpoint()
    if (
        classroom.class_graph is None  # none yet, or a world worker, whose class graph is its class server's
        or router is None
        or classroom.settings.lab.zenoh is None
    ):
        raise HTTPException(status.HTTP_404_NOT_FOUND, "this class server has no Zenoh graph of its own")
    login = classroom.zenoh_auth.class_credentials()
    return _join(router, classroom.settings.lab.zenoh.domain_id, login, _nice(classroom.settings))


def _join(router: str, domain_id: int, login: Credentials | None, nice: int | None) -> ZenohJoin:
    return ZenohJoin(
        nice=nice,
        router=router,
        domain_id=domain_id,
        user=login.user if login is not None else None,
        password=login.password if login is not None else None,
        env={
            "ROS_DOMAIN_ID": str(domain_id),
            "ZENOH_CONFIG_OVERRIDE": ";".join(graph_overrides(router, login)),
        },
    )


@router.get("/workspace")
async def workspace(lab: LabDep) -> WorkspaceInfo:
    """The folder of students' packages this lab runs from, so ``ros2lab run`` on this machine
    finds the same packages (null: the lab has none)."""
    folder = lab.settings.lab.workspace
    return WorkspaceInfo(path=str(folder.resolve()) if folder is not None else None)


@router.post("/rocket/reset", responses=responses(403))
async def reset_rocket(lab: LabDep) -> Status:
    """Put the rocket back on the pad and restart the countdown (the rocket's nodes restart)."""
    lab.rocket.reset()
    return Status(status="reset")
