"""REST for a class server (``--classroom``): join, who am I, and the instructor's controls.

In the OpenAPI document of a class server only (api.routes.build_router); on an app without
``--classroom`` every route here answers 404.
"""

from __future__ import annotations

import asyncio
from typing import Annotated, Any, Literal

from fastapi import APIRouter, Depends, HTTPException, Query, Request, Response, status
from fastapi.responses import JSONResponse
from pydantic import TypeAdapter

from api.deps import TOKEN_COOKIE, classroom_of, grant_of, set_token_cookie, token_of
from api.errors import status_for
from api.protocol.classroom import (
    Broadcast,
    BroadcastRequest,
    ClassGraph,
    ClassWorkers,
    ClassWorld,
    ClassWorlds,
    HostRequest,
    Joined,
    JoinRequest,
    Kicked,
    Me,
    QueuedJoin,
    ResetWorlds,
)
from api.protocol.responses import (
    BAD_GATEWAY,
    FORBIDDEN,
    NO_ROOM,
    NOT_FOUND,
    TOO_MANY,
    TYPE_CONFLICT,
    UNAUTHORIZED,
    UNPROCESSABLE,
    responses,
)
from api.protocol.schemas import Status
from node_runtime.transport.acl import Credentials
from server.classroom import Classroom, Grant
from server.classroom.join_queue import JoinWaits

router = APIRouter(prefix="/api/classroom", tags=["classroom"])
OPEN: dict[str, Any] = {
    "security": []
}  # OpenAPI: a route that needs no token (api/openapi.py adds the rest's)


POLL_S = 2.0  # how often a waiting join page asks again
CLASS_WORLD = TypeAdapter(ClassWorld)


def queued(waits: JoinWaits) -> JSONResponse:
    """202 for a join that waits in the queue."""
    why = "the class server is at its capacity" if waits.ahead == 0 else "joins ahead of yours wait"
    body = QueuedJoin(
        ticket=waits.waiting.ticket, ahead=waits.ahead, student=waits.waiting.student, poll_s=POLL_S, why=why
    )
    return JSONResponse(body.model_dump(), status_code=status.HTTP_202_ACCEPTED)


def _classroom(request: Request) -> Classroom:
    classroom = classroom_of(request)
    if classroom is None:
        raise HTTPException(
            status.HTTP_404_NOT_FOUND, "this server is not a class server (start it with --classroom)"
        )
    return classroom


def _grant(request: Request, classroom: Annotated[Classroom, Depends(_classroom)]) -> Grant:
    return grant_of(request, classroom)


def _instructor(grant: Annotated[Grant, Depends(_grant)]) -> Grant:
    if not grant.is_instructor:
        raise HTTPException(status.HTTP_403_FORBIDDEN, "only the instructor may do this")
    return grant


ClassroomDep = Annotated[Classroom, Depends(_classroom)]
GrantDep = Annotated[Grant, Depends(_grant)]
InstructorDep = Annotated[Grant, Depends(_instructor)]


@router.post(
    "/join",
    status_code=status.HTTP_201_CREATED,
    response_model=Joined,
    responses={
        **responses(FORBIDDEN, TYPE_CONFLICT, TOO_MANY, BAD_GATEWAY, NO_ROOM, body=True),
        202: {
            "model": QueuedJoin,
            "description": "the class is at its capacity: the join waits in the queue",
        },
    },
    openapi_extra=OPEN,
)
async def join(
    body: JoinRequest, classroom: ClassroomDep, request: Request, response: Response
) -> Joined | JSONResponse:
    """A world of one's own: the rocket and drone launches, under a token for this world only.
    Joins and wrong codes are rate-limited per client address and per class (429, Retry-After);
    at the class's capacity the join waits in a bounded queue (202 with a ticket; 503 when full).
    A name whose saved progress is another student's is 409: only the token given at that
    student's last join (the page's cookie, or a bearer) takes it (docs/checkpoints.md)."""
    address = request.client.host if request.client is not None else "unknown"
    try:
        world, token = await classroom.join(body.name, body.code, address, token_of(request))
    except JoinWaits as waits:
        return queued(waits)
    set_token_cookie(response, token)
    return Joined(world=world.name, student=world.student, token=token)


@router.post("/leave", responses=responses(), openapi_extra=OPEN)
async def leave(response: Response) -> Status:
    """Forget this browser's token (the world stays until the instructor removes it)."""
    response.delete_cookie(TOKEN_COOKIE, path="/")
    return Status(status="left")


@router.get("/me", responses=responses(UNAUTHORIZED))
async def me(grant: GrantDep, classroom: ClassroomDep) -> Me:
    """Whose token this is: a student and their world, or the instructor (with the class code)."""
    code = classroom.code if grant.is_instructor else None
    return Me(role=grant.role, world=grant.world, name=grant.name, class_code=code)


@router.get("/worlds", responses=responses(UNAUTHORIZED, FORBIDDEN))
async def worlds(_: InstructorDep, classroom: ClassroomDep) -> ClassWorlds:
    """Every world: its student, keys held, rocket phase, drone position, crashed nodes."""
    worlds = await classroom.describe_all()  # checked against ClassWorld here
    return ClassWorlds.model_validate(
        {"class_code": classroom.code, "max_worlds": classroom.class_settings.max_worlds, "worlds": worlds}
    )


@router.get("/workers", responses=responses(UNAUTHORIZED, FORBIDDEN))
async def workers(_: InstructorDep, classroom: ClassroomDep) -> ClassWorkers:
    """Where worlds can go: this server's own room, and each world worker that answers now."""
    directory, started = classroom.workers, classroom.local_workers  # a world worker has none
    found = await asyncio.to_thread(directory.discover) if directory is not None else []
    return ClassWorkers.model_validate(
        {
            "local": {
                "worlds": classroom.hosted_here,
                "max_worlds": classroom.local_capacity,
                "cpu": classroom.cpu.read().describe(),
            },
            "workers": [ref.describe() for ref in found],
            "started_here": started.describe() if started is not None else [],
            "spread": started.describe_spread() if started is not None else None,
        }
    )


@router.get("/graph", responses=responses(UNAUTHORIZED, FORBIDDEN, NOT_FOUND))
async def class_graph(_: InstructorDep, classroom: ClassroomDep) -> ClassGraph:
    """The class's own ROS domain (``GET /api/zenoh/join`` without a world gives its login): what is
    bridged from each world, as ROS 2's domain_bridge with a namespace per world."""
    bridge = classroom.class_graph  # a world worker's is its class server's
    if bridge is None or classroom.settings.lab.zenoh is None:
        raise HTTPException(status.HTTP_404_NOT_FOUND, "this class server has no Zenoh graph of its own")
    return ClassGraph(
        domain_id=classroom.settings.lab.zenoh.domain_id,
        topics=bridge.routes(),
        samples_out=bridge.stats.out,
        samples_in=bridge.stats.into,
        dropped=bridge.stats.dropped,
        calls=bridge.stats.calls,
        names_refused=bridge.refused_names(),
        calls_refused=bridge.stats.refused,
    )


@router.post(
    "/host",
    status_code=status.HTTP_201_CREATED,
    responses=responses(UNAUTHORIZED, FORBIDDEN, NOT_FOUND, TYPE_CONFLICT, TOO_MANY, body=True),
)
async def host(body: HostRequest, _: InstructorDep, classroom: ClassroomDep) -> ClassWorld:
    """On a world worker: start the world its class server placed here."""
    login = Credentials(body.zenoh_user, body.zenoh_password or "") if body.zenoh_user is not None else None
    world = await classroom.host(
        body.world,
        body.student,
        body.domain_id,
        body.launch,
        body.launch_args,
        login,
        body.router_socket,
        body.progress,
    )
    return CLASS_WORLD.validate_python(world.describe())


@router.post(
    "/worlds/{name}/reset", responses=responses(UNAUTHORIZED, FORBIDDEN, NOT_FOUND, TOO_MANY, BAD_GATEWAY)
)
async def reset_world(name: str, grant: GrantDep, classroom: ClassroomDep) -> ClassWorld:
    """Start a world over (every node, the 3D view): the instructor any, a student their own, as
    one of their writes and at most ``world_resets_hz`` a second."""
    if not grant.is_instructor and grant.world != name:
        raise HTTPException(
            status.HTTP_403_FORBIDDEN, f"your token is for world {grant.world!r}, not {name!r}"
        )
    if not grant.is_instructor:
        classroom.charge_reset(name)
    world = await classroom.reset(name)
    return CLASS_WORLD.validate_python(world.describe())


@router.post("/reset", responses=responses(UNAUTHORIZED, FORBIDDEN, NOT_FOUND, BAD_GATEWAY))
async def reset_all(_: InstructorDep, classroom: ClassroomDep) -> ResetWorlds:
    """Start every world over; answers the worlds reset."""
    names = list(classroom.worlds)
    for name in names:
        await classroom.reset(name)
    return ResetWorlds(reset=names)


@router.delete("/worlds/{name}", responses=responses(UNAUTHORIZED, FORBIDDEN, NOT_FOUND))
async def kick(
    name: str,
    _: InstructorDep,
    classroom: ClassroomDep,
    workspace: Literal["remove"] | None = Query(
        None, description="a world worker: remove the world's workspace too (the class server always does)"
    ),
) -> Kicked:
    """Remove a student's world and its workspace; their token stops working at once."""
    world = await classroom.kick(name, remove_workspace=workspace == "remove")
    return Kicked(kicked=world.name, student=world.student)


@router.post("/broadcast", responses=responses(UNAUTHORIZED, FORBIDDEN, NOT_FOUND, UNPROCESSABLE, body=True))
async def broadcast(body: BroadcastRequest, _: InstructorDep, classroom: ClassroomDep) -> Broadcast:
    """Publish one message in every world (a setpoint, a start signal); a world whose graph
    refuses it (another type on that topic, say) is listed with the reason."""
    reached: list[str] = []
    refused: dict[str, str] = {}
    for name, world in classroom.worlds.items():
        if world.lab is None:
            continue  # a worker's world: its worker publishes it, below
        try:
            world.lab.publish(body.topic, body.msg, body.type)
        except Exception as exc:
            if status_for(exc) is None:  # a bug, not a refusal: the error net has it
                raise
            refused[name] = str(exc)
        else:
            reached.append(name)
    far_reached, far_refused = await classroom.broadcast_on_workers(body.model_dump())  # a worker: none
    reached += far_reached
    refused |= far_refused
    if refused and not reached:
        raise HTTPException(status.HTTP_422_UNPROCESSABLE_CONTENT, f"no world took the message: {refused}")
    return Broadcast(reached=reached, refused=refused)
