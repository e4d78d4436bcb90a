"""The class server's load and its join queue: what the instructor's panel shows (``GET
/api/classroom/load``), how a waiting join asks again (``GET /api/classroom/join/{ticket}``) and
how the instructor lets waiting joins through (``POST /api/classroom/queue/admit``). Thresholds:
server/classroom/capacity.py and docs/classroom.md."""

from __future__ import annotations

from typing import Literal

from fastapi import APIRouter, Response, status
from fastapi.responses import JSONResponse
from pydantic import BaseModel, ConfigDict, Field, TypeAdapter
from typing_extensions import TypedDict

from api.deps import set_token_cookie
from api.protocol.responses import (
    BAD_GATEWAY,
    FORBIDDEN,
    NO_ROOM,
    NOT_FOUND,
    TOO_MANY,
    UNAUTHORIZED,
    responses,
)
from api.routes.classroom import OPEN, ClassroomDep, InstructorDep, Joined, QueuedJoin, queued
from server.classroom.join_queue import JoinWaits

router = APIRouter(prefix="/api/classroom", tags=["classroom"])


class CpuOut(TypedDict):
    process_cores: float  # the process's CPU over its last window, in cores
    host_busy: float | None  # the machine's busy share (steal included)
    cores: int
    machine: str | None
    rss_mb: float | None  # the process's resident memory, MiB
    saturated: bool


class PlaceOut(TypedDict):
    place: str  # "server" (this process) or a world worker's id
    worlds: int
    max_worlds: int
    late: int | None  # None: a worker that did not say
    cpu: CpuOut | None


class WaitingOut(TypedDict):
    student: str
    world: str
    waited_s: float


class QueueOut(TypedDict):
    waiting: list[WaitingOut]
    size: int
    wait_s: float
    let_through: int
    admitted: int
    refused: int


_QUEUE = TypeAdapter(QueueOut)


class ClassLoadOut(BaseModel):
    capacity: Literal["ok", "near", "full"] = Field(
        description="ok; near: a place's CPU is busy, a world is late or little room is left (joins still "
        "go ahead); full: no place has room, or every place with room is saturated and a quarter of the "
        "worlds are late (new joins wait in the queue)"
    )
    reasons: list[str] = Field(description="why the verdict is near or full, one line each")
    worlds: int = Field(description="worlds in the class")
    late: int = Field(
        description="worlds late now: a timer of theirs ran over 50 ms after its deadline (median of its "
        "last 20 calls) or is 1 s overdue now (a stalled loop)"
    )
    room: int = Field(description="worlds that fit by count, over every place and the class's max_worlds")
    places: list[PlaceOut] = Field(
        description="each place worlds run: 'server' (this process) or a world worker's id, with worlds, "
        "max_worlds, late and cpu (process_cores in cores, host_busy share, cores, rss_mb in MiB, saturated)"
    )
    queue: QueueOut = Field(
        description="joins waiting (student, world, waited_s), the queue's size and wait_s, let_through "
        "(joins the instructor let past a full verdict), admitted and refused so far"
    )


class LetThrough(BaseModel):
    model_config = ConfigDict(strict=True, extra="forbid")
    count: int = Field(default=1, ge=1, le=100, description="waiting joins to let in past a full verdict")


@router.get("/load", responses=responses(UNAUTHORIZED, FORBIDDEN, NOT_FOUND))
async def load(_: InstructorDep, classroom: ClassroomDep) -> ClassLoadOut:
    """The instructor's token only. The class server's load: each place's worlds, CPU and memory,
    the late worlds, the capacity verdict, and the join queue."""
    places, capacity, queue = await classroom.class_load()
    return ClassLoadOut.model_validate(
        {"capacity": capacity.verdict, "reasons": list(capacity.reasons), "worlds": capacity.worlds,
         "late": capacity.late, "room": capacity.room, "places": [p.describe() for p in places],
         "queue": queue}
    )  # fmt: skip


@router.get(
    "/join/{ticket}",
    status_code=status.HTTP_201_CREATED,
    response_model=Joined,
    responses={
        **responses(NOT_FOUND, TOO_MANY, BAD_GATEWAY, NO_ROOM),
        202: {"model": QueuedJoin, "description": "still waiting: ask again in poll_s"},
    },
    openapi_extra=OPEN,
)
async def poll(ticket: str, classroom: ClassroomDep, response: Response) -> Joined | JSONResponse:
    """A waiting join asks again (the ticket is its secret): 201 with the world and its token once
    admitted, 202 while it waits, 503 with Retry-After once it waited too long."""
    try:
        world, token = await classroom.poll_join(ticket)  # a world worker: 404
    except JoinWaits as waits:
        return queued(waits)
    set_token_cookie(response, token)
    return Joined(world=world.name, student=world.student, token=token)


@router.post("/queue/admit", responses=responses(UNAUTHORIZED, FORBIDDEN, NOT_FOUND, body=True))
async def let_through(body: LetThrough, _: InstructorDep, classroom: ClassroomDep) -> QueueOut:
    """The instructor's token only. Let ``count`` waiting joins (oldest first) start their worlds
    though the class is at its capacity; answers the queue."""
    return _QUEUE.validate_python(classroom.let_through(body.count))  # a world worker: 404
