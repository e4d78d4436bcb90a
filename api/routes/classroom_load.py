"""The class server's load and its join queue: what the instructor's panel shows (``GET
/api/classroom/load``), how a waiting join asks again (``GET /api/classroom/join/{ticket}``) and
how the instructor lets waiting joins through (``POST /api/classroom/queue/admit``). Thresholds:
server/classroom/capacity.py and docs/classroom.md."""

from __future__ import annotations

from fastapi import APIRouter, Response, status
from fastapi.responses import JSONResponse
from pydantic import TypeAdapter

from api.deps import set_token_cookie
from api.protocol.classroom import ClassLoadOut, Joined, LetThrough, QueuedJoin, QueueOut
from api.protocol.responses import (
    BAD_GATEWAY,
    FORBIDDEN,
    NO_ROOM,
    NOT_FOUND,
    TOO_MANY,
    UNAUTHORIZED,
    responses,
)
from api.routes.classroom import OPEN, ClassroomDep, InstructorDep, queued
from server.classroom.join_queue import JoinWaits

router = APIRouter(prefix="/api/classroom", tags=["classroom"])
_QUEUE = TypeAdapter(QueueOut)


@router.get("/load", responses=responses(UNAUTHORIZED, FORBIDDEN, NOT_FOUND))
async def load(_: InstructorDep, classroom: ClassroomDep) -> ClassLoadOut:
    """The instructor's token only. The class server's load: each place's worlds, CPU and memory,
    the late worlds, the capacity verdict, and the join queue."""
    places, capacity, queue = await classroom.class_load()
    return ClassLoadOut.model_validate(
        {
            "capacity": capacity.verdict,
            "reasons": list(capacity.reasons),
            "worlds": capacity.worlds,
            "late": capacity.late,
            "room": capacity.room,
            "places": [p.describe() for p in places],
            "machines": [m.describe() for m in capacity.machines],
            "queue": queue,
        }
    )


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
