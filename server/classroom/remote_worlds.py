"""What the class server asks of the worlds its world workers host: how each is, a broadcast into
each, and its end. Each worker is asked once for all of this class's worlds on it."""

from __future__ import annotations

import logging
from collections.abc import Mapping
from typing import Any

from server.classroom.errors import ClassroomError
from server.classroom.workers import WorkerDirectory, WorkerRef
from server.classroom.world import World

log = logging.getLogger("classroom")
OnWorkers = dict[str, tuple[WorkerRef, list[str]]]  # worker id → that worker, the worlds it hosts


def on_workers(worlds: Mapping[str, World]) -> OnWorkers:
    """Worker id → that worker and the names of the worlds it hosts for this class (not those
    it lost: they are being started again, and count nowhere until they are)."""
    out: OnWorkers = {}
    for world in worlds.values():
        if world.worker is not None and world.lost is None:
            out.setdefault(world.worker.id, (world.worker, []))[1].append(world.name)
    return out


async def worker_reports(
    workers: WorkerDirectory | None, worlds: Mapping[str, World]
) -> tuple[dict[tuple[str, str], dict[str, Any]], dict[str, str]]:
    """What each world worker reports of the worlds it hosts for this class, by (worker id,
    world); and why each worker that could not answer did not."""
    reports: dict[tuple[str, str], dict[str, Any]] = {}
    errors: dict[str, str] = {}
    for ref, names in on_workers(worlds).values():
        assert workers is not None
        try:
            listed = await workers.checked(ref, "GET", "/api/classroom/worlds")
        except ClassroomError as exc:
            errors[ref.id] = str(exc)
            continue
        reports.update(
            {(ref.id, str(w.get("world"))): w for w in listed.get("worlds", []) if w.get("world") in names}
        )
    return reports, errors


async def describe_worlds(
    workers: WorkerDirectory | None, worlds: Mapping[str, World]
) -> list[dict[str, Any]]:
    """Every world as the instructor's page shows it: its own description, over what its world
    worker reports of it (and why that worker did not answer, if it did not)."""
    reports, errors = await worker_reports(workers, worlds)
    out = []
    for world in worlds.values():
        mine = world.describe()
        if world.worker is not None:
            mine = {**reports.get((world.worker.id, world.name), {}), **mine}
            if world.worker.id in errors:
                mine["worker_error"] = errors[world.worker.id]
        out.append(mine)
    return out


async def broadcast(
    workers: WorkerDirectory | None, worlds: Mapping[str, World], body: dict[str, Any]
) -> tuple[list[str], dict[str, str]]:
    """The instructor's broadcast, published by each world worker in the worlds it hosts."""
    reached: list[str] = []
    refused: dict[str, str] = {}
    for ref, names in on_workers(worlds).values():
        assert workers is not None
        try:
            answer = await workers.checked(ref, "POST", "/api/classroom/broadcast", body=body)
        except ClassroomError as exc:
            refused |= dict.fromkeys(names, str(exc))
            continue
        reached += [n for n in answer.get("reached", []) if n in names]
        refused |= {n: str(why) for n, why in answer.get("refused", {}).items() if n in names}
    return reached, refused


async def remote_drones(
    workers: WorkerDirectory | None, worlds: Mapping[str, World]
) -> dict[str, list[float] | None]:
    """Each worker world's drone as its worker reports it (None: not a position)."""
    reports, _errors = await worker_reports(workers, worlds)
    found: dict[str, list[float] | None] = {}
    for (_wid, name), report in reports.items():
        drone = report.get("drone")
        if isinstance(drone, list) and len(drone) == 3 and all(isinstance(v, int | float) for v in drone):
            found[name] = [float(v) for v in drone]
        else:
            found[name] = None
    return found


async def end_remote(workers: WorkerDirectory, world: World, *, remove_workspace: bool = False) -> None:
    """Ask ``world``'s worker to end it (and remove its workspace there: the student is removed);
    a worker that is gone took its world with it."""
    assert world.worker is not None
    query = "?workspace=remove" if remove_workspace else ""
    try:
        await workers.checked(world.worker, "DELETE", f"/api/classroom/worlds/{world.name}{query}")
    except ClassroomError as exc:
        log.warning("world %s: %s", world.name, exc)
