"""REST for a class server (``--classroom``): join, who am I, and the instructor's controls.

In the OpenAPI document of a class server only (api.routes.build_router); on an app without
``--classroom`` every route here answers 404.
"""

from __future__ import annotations

import asyncio
from typing import Annotated, Any, Literal, Required

from fastapi import APIRouter, Depends, HTTPException, Query, Request, Response, status
from fastapi.responses import JSONResponse
from pydantic import BaseModel, ConfigDict, Field, model_validator, with_config
from typing_extensions import TypedDict

from api.deps import TOKEN_COOKIE, classroom_of, grant_of, set_token_cookie, token_of
from api.errors import status_for
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
from node_runtime.transport.acl import Credentials
from server.classroom import Classroom, Grant
from server.classroom.join_queue import JoinWaits

router = APIRouter(prefix="/api/classroom", tags=["classroom"])
OPEN: dict[str, Any] = {
    "security": []
}  # OpenAPI: a route that needs no token (api/openapi.py adds the rest's)


class JoinRequest(BaseModel):
    model_config = ConfigDict(strict=True, extra="forbid")
    name: str = Field(min_length=1, max_length=64, examples=["Ada Lovelace"])
    code: str = Field(min_length=1, max_length=16, examples=["K7PX2M"])


class BroadcastRequest(BaseModel):
    model_config = ConfigDict(strict=True, extra="forbid")
    topic: str = Field(min_length=1, max_length=256, examples=["/uav/input/position"])
    msg: dict[str, Any] = Field(examples=[{"x": 5.0, "y": 5.0, "z": 10.0}])
    type: str | None = Field(default=None, max_length=128, examples=["geometry_msgs/msg/Vector3"])


class HostRequest(BaseModel):
    """A class server placing a world on this world worker."""

    model_config = ConfigDict(strict=True, extra="forbid")
    world: str = Field(min_length=1, max_length=32, pattern=r"^[a-z_][a-z0-9_]*$")
    student: str = Field(min_length=1, max_length=64)
    domain_id: int = Field(ge=1, le=232)
    launch: str = Field(min_length=1, max_length=256)
    launch_args: dict[str, str] = Field(default_factory=dict, max_length=32)
    # The world's own Zenoh login, drawn by the class server (its graph joins the router with it).
    zenoh_user: str | None = Field(None, min_length=1, max_length=64, pattern=r"^[A-Za-z0-9_-]+$")
    zenoh_password: str | None = Field(None, min_length=1, max_length=64, pattern=r"^[A-Za-z0-9]+$")
    # The class router's Unix socket: a worker on its machine runs the world's students' nodes
    # in a sandbox that reaches the router there.
    router_socket: str | None = Field(None, min_length=2, max_length=256, pattern=r"^/[A-Za-z0-9_./-]+$")
    # The class server's copy of the world's progress, for a worker whose own folder lacks it
    # (server/world/checkpoints/handover.py's form).
    progress: dict[str, Any] | None = None

    @model_validator(mode="after")
    def _login_whole(self) -> HostRequest:
        if (self.zenoh_user is None) != (self.zenoh_password is None):
            raise ValueError("zenoh_user and zenoh_password come together")
        return self


class Joined(BaseModel):
    world: str = Field(examples=["ada_lovelace"])
    student: str = Field(examples=["Ada Lovelace"])
    token: str = Field(description="this world's bearer token; the page keeps it in an HTTP-only cookie")


class QueuedJoin(BaseModel):
    ticket: str = Field(description="the join's secret: ask again with GET /api/classroom/join/{ticket}")
    ahead: int = Field(description="joins waiting ahead of this one")
    student: str
    poll_s: float = Field(description="ask again this often, or the join leaves the queue")
    why: str = Field(description="why it waits")


POLL_S = 2.0  # how often a waiting join page asks again


def queued(waits: JoinWaits) -> JSONResponse:
    """202 for a join that waits in the queue."""
    why = "the class server is at its capacity" if waits.ahead == 0 else "joins ahead of yours wait"
    body = QueuedJoin(ticket=waits.waiting.ticket, ahead=waits.ahead, student=waits.waiting.student,
                      poll_s=POLL_S, why=why)  # fmt: skip
    return JSONResponse(body.model_dump(), status_code=status.HTTP_202_ACCEPTED)


class Me(BaseModel):
    role: Literal["student", "instructor"]
    world: str | None = Field(description="the student's world; none for the instructor")
    name: str
    class_code: str | None = Field(default=None, description="only for the instructor")


class RocketState(TypedDict):
    phase: str
    altitude_m: float


@with_config(ConfigDict(extra="allow"))
class ClassWorld(TypedDict, total=False):
    """One world as the instructor's page shows it; the lab's own figures only while it runs,
    and a world on a world worker as its worker reports them."""

    world: Required[str]
    student: Required[str]
    worker: Required[str | None]  # the world worker hosting it; null on this server
    lost: Required[str | None]  # why it cannot be reached now
    worker_error: str  # why its world worker did not answer
    keys_held: list[str]
    rocket: RocketState | None
    drone: list[float] | None  # x, y, z (m); null before the first fix
    crashed_nodes: list[str]


class ClassWorlds(BaseModel):
    class_code: str
    max_worlds: int
    worlds: list[ClassWorld] = Field(
        description="each world: student, where it runs, keys held, rocket phase, drone, crashed nodes"
    )


class ClassWorkers(BaseModel):
    local: dict[str, Any] = Field(
        description="this server's own worlds, how many it takes, and its CPU (process_cores: this process's "
        "CPU over the last window in cores; host_busy: the machine's busy share; machine: a digest of its "
        "boot id; saturated: the process uses 0.85 core or the machine is 90 % busy. No new world goes to a "
        "full process while another place has room, nor to a busy machine while another machine has room)"
    )
    workers: list[dict[str, Any]] = Field(
        description="each world worker that answers now, with its load: worlds, max_worlds and cpu, as for local"
    )
    started_here: list[dict[str, Any]] = Field(
        default_factory=list,
        description="the world workers this server started on its machine (--workers): id, pid (null while "
        "down), restarts, and given_up once it kept dying",
    )
    spread: dict[str, int] | None = Field(
        default=None,
        description="with --workers auto: another world worker on this machine each at_worlds worlds, at most "
        "up_to (the machine's spare cores); null when workers start only as --workers N said",
    )


class ClassGraph(BaseModel):
    domain_id: int = Field(description="the class's own ROS domain, where every world shows under /<world>")
    topics: dict[str, list[str]] = Field(
        description="by world, each bridged topic or service: 'out' (the world publishes it; 'out*' while "
        "something in the class domain subscribes, so it crosses now), 'in' (the world subscribes to it) "
        "or 'srv' (the world serves it; a call in the class domain goes to that world's server)",
        examples=[
            {"ada": ["in /ada/uav/input/position", "out* /ada/uav/sensors/gps", "srv /ada/rocket/reset"]}
        ],
    )
    samples_out: int = Field(description="samples passed from worlds into the class domain")
    samples_in: int = Field(description="samples passed from the class domain into worlds")
    dropped: int = Field(description="samples dropped (no rmw_zenoh attachment, or a watcher too slow)")
    calls: int = Field(description="service calls in the class domain answered by a world's server")
    names_refused: dict[str, int] = Field(
        description="by world, its entities not bridged because their name is not a fully qualified ROS "
        "name (or their type is not a plain type name): 'm/uav/sensors/gps' in world ada would be /adam/...",
        examples=[{"ada": 1}],
    )
    calls_refused: int = Field(
        description="service calls refused: no rmw_zenoh attachment, a key pattern instead of one service, "
        "or too many waiting on one world"
    )


class Broadcast(BaseModel):
    reached: list[str]
    refused: dict[str, str] = Field(description="world: why its graph refused the message")


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
async def leave(response: Response) -> dict[str, str]:
    """Forget this browser's token (the world stays until the instructor removes it)."""
    response.delete_cookie(TOKEN_COOKIE, path="/")
    return {"status": "left"}


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
    return ClassWorkers(
        local={
            "worlds": classroom.hosted_here,
            "max_worlds": classroom.local_capacity,
            "cpu": classroom.cpu.read().describe(),
        },
        workers=[ref.describe() for ref in found],
        started_here=started.describe() if started is not None else [],
        spread=started.describe_spread() if started is not None else None,
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
async def host(body: HostRequest, _: InstructorDep, classroom: ClassroomDep) -> dict[str, Any]:
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
    return world.describe()


@router.post(
    "/worlds/{name}/reset", responses=responses(UNAUTHORIZED, FORBIDDEN, NOT_FOUND, TOO_MANY, BAD_GATEWAY)
)
async def reset_world(name: str, grant: GrantDep, classroom: ClassroomDep) -> dict[str, Any]:
    """Start a world over (every node, the 3D view): the instructor any, a student their own, as
    one of their writes and at most ``world_resets_hz`` a second."""
    if not grant.is_instructor and grant.world != name:
        raise HTTPException(
            status.HTTP_403_FORBIDDEN, f"your token is for world {grant.world!r}, not {name!r}"
        )
    if not grant.is_instructor:
        classroom.charge_reset(name)
    world = await classroom.reset(name)
    return world.describe()


@router.post("/reset", responses=responses(UNAUTHORIZED, FORBIDDEN, NOT_FOUND, BAD_GATEWAY))
async def reset_all(_: InstructorDep, classroom: ClassroomDep) -> dict[str, list[str]]:
    """Start every world over; answers the worlds reset."""
    names = list(classroom.worlds)
    for name in names:
        await classroom.reset(name)
    return {"reset": names}


@router.delete("/worlds/{name}", responses=responses(UNAUTHORIZED, FORBIDDEN, NOT_FOUND))
async def kick(
    name: str,
    _: InstructorDep,
    classroom: ClassroomDep,
    workspace: Literal["remove"] | None = Query(
        None, description="a world worker: remove the world's workspace too (the class server always does)"
    ),
) -> dict[str, str]:
    """Remove a student's world and its workspace; their token stops working at once."""
    world = await classroom.kick(name, remove_workspace=workspace == "remove")
    return {"kicked": world.name, "student": world.student}


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
