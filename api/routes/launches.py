"""REST: launch files and single nodes into the running graph (``ros2 launch``, ``ros2 run``).

Handlers are ``async def`` so they run on the loop that owns the bus, never in a worker thread
(reading a launch file, which touches no node, is the one thing done in one).
Errors are mapped in api/errors.py; handlers do not catch.
"""

from __future__ import annotations

import asyncio

from fastapi import APIRouter, status

from api.deps import LabDep
from api.protocol.launches import LaunchGroupOut, LaunchOutputOut, LaunchRequest, RunRequest
from api.protocol.responses import NOT_FOUND, TOO_MANY, responses
from server.packages.launch_files import launch_file

router = APIRouter(prefix="/api", tags=["launch"], responses=responses())


@router.post(
    "/launch", status_code=status.HTTP_201_CREATED, responses=responses(NOT_FOUND, TOO_MANY, body=True)
)
async def launch(body: LaunchRequest, lab: LabDep) -> LaunchGroupOut:
    """Start a launch file's nodes; a node that fails to start is reported, the others run."""
    path = launch_file(lab.packages, body.package, body.file, confined=lab.settings.confines_paths)
    # Read off the loop: a Python launch file is evaluated in a process of its own. Reading
    # touches no node; the nodes start on the loop.
    description = await asyncio.to_thread(lab.launcher.parse, path, body.args)
    return LaunchGroupOut.model_validate(lab.launch_groups.launch(path, body.args, description).describe())


@router.post("/run", status_code=status.HTTP_201_CREATED, responses=responses(NOT_FOUND, TOO_MANY, body=True))
async def run(body: RunRequest, lab: LabDep) -> LaunchGroupOut:
    """Start one node from a package, as ``ros2 run`` (``--ros-args -p`` / ``-r`` as fields)."""
    group = lab.launch_groups.run(body.package, body.executable, body.name, body.parameters, body.remappings)
    return LaunchGroupOut.model_validate(group.describe())


@router.get("/launches")
async def launches(lab: LabDep) -> list[LaunchGroupOut]:
    return [LaunchGroupOut.model_validate(g.describe()) for g in lab.launch_groups.values()]


@router.get("/launches/{group_id}/output", responses=responses(NOT_FOUND))
async def output(group_id: str, lab: LabDep) -> LaunchOutputOut:
    """One launch or run as ``GET /launches`` gives it, and what each of its node processes
    printed: the last 200 lines (each cut at 4096 characters) and how many in all, so a reader
    that asks again knows which lines are new."""
    return LaunchOutputOut.model_validate(lab.launch_groups.get(group_id).output())


@router.delete("/launches/{group_id}", responses=responses(NOT_FOUND, 403))
async def stop(group_id: str, lab: LabDep) -> LaunchGroupOut:
    """Stop the nodes of one launch or run, as Ctrl-C on ``ros2 launch`` does."""
    return LaunchGroupOut.model_validate(lab.launch_groups.stop(group_id).describe())
