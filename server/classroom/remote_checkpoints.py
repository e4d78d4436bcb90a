"""The checkpoints of the worlds world workers host, for the instructor's table, its CSV and the
reports' zip: each worker is asked once for all of this class's worlds on it, every worker at
once and each within ``ASK_TIMEOUT_S``. A world whose worker does not answer (or that is between
workers) gets a row whose every cell is ``unreachable``, with the reason, rather than no row."""

from __future__ import annotations

import asyncio
import io
import zipfile
from collections.abc import Awaitable, Mapping, Sequence
from typing import Any, TypeVar

from server.classroom.errors import ClassroomError, WorkerFailedError, WorkerTimeoutError
from server.classroom.remote_worlds import on_workers
from server.classroom.workers import WorkerDirectory, WorkerRef
from server.classroom.world import World

ASK_TIMEOUT_S = 5.0  # a worker answers in milliseconds; one that does not is shown as unreachable
MAX_ZIP_ENTRIES = 4 * 256  # two files per world, a worker's worlds at most (settings' max_worlds)
MAX_UNZIPPED_BYTES = 256 * 1024 * 1024
UNREACHABLE = "unreachable"
T = TypeVar("T")


async def _bounded(worker: WorkerRef, call: Awaitable[T], timeout_s: float) -> T:
    try:
        return await asyncio.wait_for(call, timeout_s)
    except TimeoutError:
        raise WorkerTimeoutError(
            f"world worker {worker.id!r} did not answer within {timeout_s:g} s"
        ) from None


def _why(worker: WorkerRef, exc: BaseException) -> str:
    """What went wrong asking ``worker`` (a cancellation is not an answer: it goes on up)."""
    if not isinstance(exc, Exception):
        raise exc
    if isinstance(exc, ClassroomError):
        return str(exc)
    return f"world worker {worker.id!r} answered with what is not a checkpoint table ({type(exc).__name__})"


def unreachable_row(world: World, checkpoints: Sequence[str], reason: str) -> dict[str, Any]:
    cells = {name: {"state": UNREACHABLE, "done_at": None} for name in checkpoints}
    return {
        "name": world.student,
        "world": world.name,
        "cells": cells,
        "answers": {},
        "joined": True,
        "unreachable": reason,
    }


def _remote(worlds: Mapping[str, World]) -> list[World]:
    return [w for w in worlds.values() if w.lab is None]


def _missing_reason(world: World, errors: dict[str, str]) -> str:
    if world.worker is None or world.lost is not None:
        return "its world worker was lost: the world is starting again elsewhere"
    return errors.get(world.worker.id, f"world worker {world.worker.id!r} did not list it")


async def checkpoint_rows(
    workers: WorkerDirectory | None,
    worlds: Mapping[str, World],
    checkpoints: Sequence[str],
    timeout_s: float = ASK_TIMEOUT_S,
) -> tuple[list[dict[str, Any]], dict[str, str]]:
    """A row for each world on a world worker: as its worker keeps it, else an unreachable one;
    and why each worker that could not answer did not."""
    asked = list(on_workers(worlds).values())

    async def ask(ref: WorkerRef) -> Any:
        assert workers is not None
        return await _bounded(ref, workers.checked(ref, "GET", "/api/classroom/checkpoints"), timeout_s)

    answers = await asyncio.gather(*(ask(ref) for ref, _names in asked), return_exceptions=True)
    found: dict[str, dict[str, Any]] = {}
    errors: dict[str, str] = {}
    for (ref, names), answer in zip(asked, answers, strict=True):
        if not isinstance(answer, dict) or not isinstance(rows := answer.get("students"), list):
            errors[ref.id] = _why(ref, answer if isinstance(answer, BaseException) else TypeError())
            continue
        found |= {row["world"]: row for row in rows if isinstance(row, dict) and row.get("world") in names}
    rows = [
        found.get(w.name) or unreachable_row(w, checkpoints, _missing_reason(w, errors))
        for w in _remote(worlds)
    ]
    return rows, errors


def _unzip(worker: WorkerRef, data: bytes, names: Sequence[str]) -> list[tuple[str, bytes]]:
    """The reports of ``names`` in a worker's zip; WorkerFailedError for a zip too large to take."""
    wanted = {f"{n}.{ext}" for n in names for ext in ("json", "html")}
    try:
        with zipfile.ZipFile(io.BytesIO(data)) as archive:
            entries = archive.infolist()
            if len(entries) > MAX_ZIP_ENTRIES or sum(e.file_size for e in entries) > MAX_UNZIPPED_BYTES:
                raise WorkerFailedError(f"world worker {worker.id!r} sent more reports than it can host")
            return [(e.filename, archive.read(e)) for e in entries if e.filename in wanted]
    except (zipfile.BadZipFile, ValueError) as exc:
        raise WorkerFailedError(f"world worker {worker.id!r} sent no zip: {exc}") from None


async def report_files(
    workers: WorkerDirectory | None, worlds: Mapping[str, World], timeout_s: float = ASK_TIMEOUT_S
) -> tuple[list[tuple[str, bytes]], dict[str, str]]:
    """Each world worker's signed reports of this class's worlds on it (JSON and HTML, as its
    zip names them); and why each world without reports has none."""
    asked = list(on_workers(worlds).values())

    async def ask(ref: WorkerRef, names: list[str]) -> list[tuple[str, bytes]]:
        assert workers is not None
        reply = await _bounded(ref, workers.call(ref, "GET", "/api/classroom/checkpoints/reports"), timeout_s)
        if reply.status_code != 200:
            raise WorkerFailedError(f"world worker {ref.id!r} answered {reply.status_code}")
        return _unzip(ref, reply.content, names)

    answers = await asyncio.gather(*(ask(ref, names) for ref, names in asked), return_exceptions=True)
    files: list[tuple[str, bytes]] = []
    errors: dict[str, str] = {}
    for (ref, _names), answer in zip(asked, answers, strict=True):
        if isinstance(answer, BaseException):
            errors[ref.id] = _why(ref, answer)
        else:
            files += answer
    have = {name.rpartition(".")[0] for name, _data in files}
    missing = {w.name: _missing_reason(w, errors) for w in _remote(worlds) if w.name not in have}
    return files, missing
