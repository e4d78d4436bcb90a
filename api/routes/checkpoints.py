"""REST: the world's checkpoints (docs/checkpoints.md): their state for the page's guide, the
answers, the page's capture, the signed report and its verification; and for a class server's
instructor the class's table (JSON or CSV) and every report in one zip."""

from __future__ import annotations

import re
from typing import Annotated, Any, Literal

from fastapi import APIRouter, Depends, Path, Query, Request, Response
from pydantic import TypeAdapter
from starlette.requests import HTTPConnection

from api.deps import LabDep, classroom_of, grant_of, lab_of
from api.protocol.checkpoints import (
    AnswerBody,
    Captured,
    Checkpoints,
    ClassCheckpoints,
    KnownCopies,
    ProgressCopies,
    Question,
    Released,
    Report,
    VerifyResult,
)
from api.protocol.responses import NOT_FOUND, TYPE_CONFLICT, UNAUTHORIZED, UNPROCESSABLE, responses
from api.routes.classroom import ClassroomDep, InstructorDep
from server.world.checkpoints.catalog import load
from server.world.checkpoints.class_table import Row, reports_zip, table, table_csv
from server.world.checkpoints.handover import tag, to_wire
from server.world.checkpoints.report import build, signed_files
from server.world.checkpoints.saved import Snapshot
from server.world.checkpoints.signing import ReportSigner
from server.world.checkpoints.view import world_view
from server.world.lab import Lab

router = APIRouter(prefix="/api/checkpoints", tags=["checkpoints"], responses=responses())
class_router = APIRouter(prefix="/api/classroom/checkpoints", tags=["classroom"])

MAX_CAPTURE_BODY = 2 * 1024 * 1024
MAX_REPORT_BODY = 8 * 1024 * 1024
# A world handed to a world worker with its progress (its file, and its captures in base64).
MAX_HOST_BODY = 24 * 1024 * 1024
# Bodies larger than the app's limit (a PNG, a report with its pictures): GuardMiddleware's.
LARGE_BODIES = (
    (re.compile(r"/api/checkpoints/[A-Za-z0-9_]+/capture"), MAX_CAPTURE_BODY),
    (re.compile(r"/api/checkpoints/verify"), MAX_REPORT_BODY),
    (re.compile(r"/api/classroom/host"), MAX_HOST_BODY),
)
QUESTION = TypeAdapter(Question)
CLASS_TABLE = TypeAdapter(ClassCheckpoints)


def signer(conn: HTTPConnection) -> ReportSigner:
    """The server's signing key, read (or made) in its state folder on first use."""
    state = conn.app.state
    found: ReportSigner | None = getattr(state, "report_signer", None)
    if found is None:
        found = state.report_signer = ReportSigner.in_folder(state.settings.lab.state_dir)
    return found


def _world_name(lab: Lab) -> str | None:
    return lab.bus.label


@router.get(
    "",
    responses={
        **responses(UNAUTHORIZED),
        204: {"description": "nothing changed since the version `since` names"},
    },
    response_model=Checkpoints,
)
async def checkpoints(
    lab: LabDep, since: Annotated[int | None, Query(ge=0)] = None
) -> Checkpoints | Response:
    """Every checkpoint with its state, time, steps, live progress and evidence; the questions and
    answers. ``version`` rises on any change: with ``?since=`` it, nothing new is a 204."""
    watch = lab.checkpoints
    lines, running = watch.lines(), watch.running()
    if since is not None and since == watch.version:
        return Response(status_code=204)
    return Checkpoints.model_validate(world_view(watch.progress, lines, watch.version, running))


@router.put("/answers/{question}", responses=responses(UNAUTHORIZED, NOT_FOUND, 413, body=True))
async def answer(question: str, body: AnswerBody, lab: LabDep) -> Question:
    """Save the answer to ``question`` (q1, q2, q3, final); over 8 KiB is a 413 and changes nothing."""
    progress = lab.checkpoints.progress
    progress.answer(question, body.text)
    return QUESTION.validate_python(
        next(q for q in world_view(progress, {}, 0)["questions"] if q["id"] == question)
    )


@router.post("/{name}/capture", responses=responses(UNAUTHORIZED, NOT_FOUND, 413, UNPROCESSABLE))
async def capture(name: str, request: Request, lab: LabDep) -> Captured:
    """The page's PNG capture of its 3D view (at most 2 MiB), kept as checkpoint ``name``'s picture."""
    lab.checkpoints.progress.capture(name, await request.body())
    return Captured(checkpoint=name, captured=True)


@router.get(
    "/report",
    responses={
        **responses(UNAUTHORIZED),
        200: {
            "model": Report,
            "description": "the signed report: its HTML page, or (?format=json) its JSON",
            "content": {"text/html": {}, "application/json": {}},
        },
    },
    response_class=Response,
)
async def report(request: Request, lab: LabDep, format: Literal["html", "json"] = "html") -> Response:
    """The signed report to hand in: an HTML page to print, or its JSON."""
    watch = lab.checkpoints
    content = build(watch.progress, watch.lines(), _world_name(lab))
    json_file, page = signed_files(signer(request), content)
    stem = f"checkpoints-{_world_name(lab) or 'lab'}"
    media = "application/json" if format == "json" else "text/html; charset=utf-8"
    return Response(
        json_file if format == "json" else page,
        media_type=media,
        headers={"Content-Disposition": f'attachment; filename="{stem}.{format}"'},
    )


def _may_verify(request: Request) -> None:
    """Anyone this server lets in: the lab's caller, or on a class server anyone with a token."""
    classroom = classroom_of(request)
    if classroom is None:
        lab_of(request)
    else:
        grant_of(request, classroom)


@router.post("/verify", responses=responses(UNAUTHORIZED, 413))
async def verify(request: Request, _: Annotated[None, Depends(_may_verify)]) -> VerifyResult:
    """Whether a report file (its JSON or its HTML page) is one this server signed, unchanged."""
    verdict = signer(request).verify(await request.body())
    return VerifyResult(valid=verdict.valid, reason=verdict.reason, student=verdict.student)


# -- the instructor's ------------------------------------------------------------------------------
def _rows(request: Request, classroom: ClassroomDep) -> tuple[list[str], list[Any]]:
    names = [c.name for c in load(request.app.state.settings.lab.checkpoints)]
    rows = []
    for world in classroom.worlds.values():
        if world.lab is None:
            continue  # on a world worker: its worker's table has it
        watch = world.lab.checkpoints
        rows.append((world.name, watch.progress, watch.lines()))
    return names, rows


@class_router.get(
    "",
    responses={
        **responses(UNAUTHORIZED, 403),
        200: {
            "description": "the table; ?format=csv as CSV",
            "content": {"application/json": {}, "text/csv": {}},
        },
    },
    response_model=ClassCheckpoints,
)
async def class_checkpoints(
    request: Request, _: InstructorDep, classroom: ClassroomDep, format: Literal["json", "csv"] = "json"
) -> ClassCheckpoints | Response:
    """Student × checkpoint, with the times each was done, and the answers; ``?format=csv``. A
    world on a world worker that does not answer in time has every cell ``unreachable``. A student
    whose progress is saved but who has not joined since the class server started is listed with
    ``joined`` false (the CSV's last column, ``joined``: ``no``)."""
    names, rows = _rows(request, classroom)
    # Students not joined since it started, as their files keep them (a world worker keeps none).
    saved: list[Row] = [(name, progress, {}) for name, progress in classroom.not_joined()]
    view = table(names, rows, saved)
    remote, errors = await classroom.worker_checkpoints(names)  # as its world workers keep them
    view["students"] += remote
    if errors:
        view["worker_errors"] = errors
    if format == "csv":
        return Response(
            table_csv(view),
            media_type="text/csv; charset=utf-8",
            headers={"Content-Disposition": 'attachment; filename="checkpoints.csv"'},
        )
    return CLASS_TABLE.validate_python(view)


@class_router.post("/progress", responses=responses(UNAUTHORIZED, 403, body=True))
async def progress_copies(body: KnownCopies, _: InstructorDep, classroom: ClassroomDep) -> ProgressCopies:
    """The progress of each world hosted here whose tag is not the one ``known`` gives: what a
    class server copies from its world workers (server/classroom/progress_copies.py), each as
    ``{"tag", "progress": {"progress": <the progress file>, "captures": {checkpoint: base64}}}``."""
    changed: dict[str, Any] = {}
    for world in classroom.worlds.values():
        if world.lab is None:
            continue  # on a world worker: that worker is asked
        progress = world.lab.checkpoints.progress
        now = tag(progress)
        if body.known.get(world.name) != now:
            changed[world.name] = {"tag": now, "progress": to_wire(Snapshot.of(progress))}
    return ProgressCopies.model_validate({"worlds": changed})


@class_router.get(
    "/reports",
    responses={
        **responses(UNAUTHORIZED, 403),
        200: {"description": "a zip", "content": {"application/zip": {}}},
    },
    response_class=Response,
)
async def class_reports(request: Request, _: InstructorDep, classroom: ClassroomDep) -> Response:
    """Every student's signed report, JSON and HTML, in one zip (also those not joined since the
    class server started, from their saved progress); for a world on a world worker that does not
    answer in time, ``<world>.unreachable.txt`` says why."""
    files = []
    for world in classroom.worlds.values():
        if world.lab is None:
            continue
        watch = world.lab.checkpoints
        json_file, page = signed_files(signer(request), build(watch.progress, watch.lines(), world.name))
        files += [(f"{world.name}.json", json_file), (f"{world.name}.html", page)]
    for name, progress in await classroom.not_joined_with_captures():  # a world worker: none
        json_file, page = signed_files(signer(request), build(progress, {}, name))
        files += [(f"{name}.json", json_file), (f"{name}.html", page)]
    remote, missing = await classroom.worker_reports()  # as the world workers sign them
    files += remote
    files += [(f"{name}.unreachable.txt", f"{why}\n".encode()) for name, why in missing.items()]
    return Response(
        reports_zip(files),
        media_type="application/zip",
        headers={"Content-Disposition": 'attachment; filename="checkpoint-reports.zip"'},
    )


@class_router.post("/{world}/release", responses=responses(UNAUTHORIZED, 403, NOT_FOUND, TYPE_CONFLICT))
async def release(
    _: InstructorDep,
    classroom: ClassroomDep,
    world: Annotated[str, Path(pattern=r"^[a-z][a-z0-9_]{0,31}$", description="the world's name")],
) -> Released:
    """Give a saved world's progress to the next join under its name, whoever it is (a student who
    lost the cookie that proves it is them): its owner record is set aside, not removed. A world
    joined now is 409; one with no saved progress whose owner is recorded, 404."""
    student = await classroom.release_progress(world)  # a world worker: 404
    return Released(released=world, student=student)
