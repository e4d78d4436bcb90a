"""REST: launch files and single nodes into the running graph (``ros2 launch``, ``ros2 run``).

Handlers are ``async def`` so they run on the loop that owns the bus, never in a worker thread.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from fastapi import APIRouter, HTTPException, status
from pydantic import BaseModel, ConfigDict, Field

from server.launch.description import LaunchFileError
from server.packages import ExecutableNotFoundError, PackageNotFoundError

from .deps import LabDep

router = APIRouter(prefix="/api", tags=["launch"])


class LaunchRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    file: str = Field(
        description="a launch file's path, or its name inside `package`", examples=["rocket.launch"]
    )
    package: str | None = Field(default=None, examples=["rocketship"])
    args: dict[str, str] = Field(default_factory=dict, examples=[{"start_delay": "2.0"}])


class RunRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    package: str = Field(examples=["rocketship"])
    executable: str = Field(examples=["keyboard_manager.py"])
    name: str | None = None
    parameters: dict[str, Any] = Field(default_factory=dict)
    remappings: dict[str, str] = Field(default_factory=dict)


def _bad(exc: Exception) -> HTTPException:
    if isinstance(exc, (PackageNotFoundError, ExecutableNotFoundError, LookupError)):
        return HTTPException(status.HTTP_404_NOT_FOUND, str(exc))
    return HTTPException(status.HTTP_422_UNPROCESSABLE_CONTENT, str(exc))


@router.post("/launch", status_code=status.HTTP_201_CREATED)
async def launch(body: LaunchRequest, lab: LabDep) -> dict[str, Any]:
    """Start a launch file's nodes; a node that fails to start is reported, the others run."""
    try:
        path = (
            lab.packages.share_dir(body.package) / "launch" / body.file if body.package else Path(body.file)
        )
        return lab.launch_group(path, body.args).describe()
    except LaunchFileError as exc:
        raise HTTPException(status.HTTP_422_UNPROCESSABLE_CONTENT, str(exc)) from exc
    except (PackageNotFoundError, LookupError) as exc:
        raise _bad(exc) from exc


@router.post("/run", status_code=status.HTTP_201_CREATED)
async def run(body: RunRequest, lab: LabDep) -> dict[str, Any]:
    """Start one node from a package, as ``ros2 run`` (``--ros-args -p`` / ``-r`` as fields)."""
    try:
        return lab.run_node(
            body.package, body.executable, body.name, body.parameters, body.remappings
        ).describe()
    except Exception as exc:
        raise _bad(exc) from exc


@router.get("/launches")
async def launches(lab: LabDep) -> list[dict[str, Any]]:
    return [g.describe() for g in lab.launch_groups.values()]


@router.delete("/launches/{group_id}")
async def stop(group_id: str, lab: LabDep) -> dict[str, Any]:
    """Stop the nodes of one launch or run, as Ctrl-C on ``ros2 launch`` does."""
    try:
        return lab.stop_group(group_id).describe()
    except LookupError as exc:
        raise HTTPException(status.HTTP_404_NOT_FOUND, str(exc)) from exc
