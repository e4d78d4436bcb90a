"""REST: record and replay like ``ros2 bag`` (record, stop, list, download, play, stop playing).

Bags are written into the server's bag folder (``--bag-dir``) under a plain name; the download
serves the MCAP file that Foxglove, Lichtblick and ``ros2 bag info`` open.
"""

from __future__ import annotations

import asyncio
from pathlib import Path
from typing import Any

from fastapi import APIRouter, HTTPException, status
from fastapi.responses import FileResponse
from pydantic import BaseModel, ConfigDict, Field

from server.bag.manager import NAME as BAG_NAME
from server.bag.manager import BagLimitError
from server.bag.player import MAX_RATE, MIN_RATE, BagError

from .deps import LabDep

# Handlers are ``async def``: the bus belongs to the event loop (see api/publishers.py).
router = APIRouter(prefix="/api/bag", tags=["bag"])


class RecordRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    topics: list[str] = Field(default_factory=list, max_length=256, examples=[["/uav/sensors/gps"]])
    all: bool = Field(
        default=False, description="every topic but hidden ones, new ones too (ros2 bag record -a)"
    )
    name: str | None = Field(
        default=None, description="the bag's folder name; default rosbag2_YYYY_MM_DD-HH_MM_SS"
    )


class PlayRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    bag: str = Field(description="a bag's name in the bag folder, or a path to a bag folder or .mcap file")
    rate: float = Field(default=1.0, ge=MIN_RATE, le=MAX_RATE)
    loop: bool = False


def _error(exc: Exception) -> Exception:
    """The bag's own errors as statuses; the rest (bad names, types) go to the app's error map."""
    if isinstance(exc, LookupError):
        return HTTPException(status.HTTP_404_NOT_FOUND, str(exc))
    if isinstance(exc, (FileExistsError, BagLimitError)):
        return HTTPException(status.HTTP_409_CONFLICT, str(exc))
    if isinstance(exc, (BagError, ValueError)):
        return HTTPException(status.HTTP_422_UNPROCESSABLE_CONTENT, str(exc))
    return exc


@router.post("/recordings", status_code=status.HTTP_201_CREATED)
async def record(body: RecordRequest, lab: LabDep) -> dict[str, Any]:
    """Start recording the named topics (or all of them) into a new bag."""
    try:
        return lab.bags.record(body.topics, all_topics=body.all, name=body.name).describe()
    except Exception as exc:
        raise _error(exc) from exc


@router.get("/recordings")
async def list_recordings(lab: LabDep) -> list[dict[str, Any]]:
    """This run's recordings (with counts) and the older bags in the bag folder."""
    return lab.bags.list_bags()


@router.delete("/recordings/{name}")
async def stop_recording(name: str, lab: LabDep) -> dict[str, Any]:
    """Stop a recording; the bag is complete (MCAP summary, metadata.yaml) when this returns."""
    try:
        recording = lab.bags.detach_recording(name)
    except Exception as exc:
        raise _error(exc) from exc
    await asyncio.to_thread(recording.writer.close)  # the disk, not the loop, waits
    return recording.describe()


@router.get("/recordings/{name}/download", response_class=FileResponse)
async def download(name: str, lab: LabDep) -> FileResponse:
    """The bag's MCAP file."""
    try:
        path = lab.bags.bag_file(name)
    except Exception as exc:
        raise _error(exc) from exc
    return FileResponse(path, media_type="application/octet-stream", filename=path.name)


@router.get("/recordings/{name}/metadata.yaml", response_class=FileResponse)
async def metadata(name: str, lab: LabDep) -> FileResponse:
    """The bag's metadata.yaml, as ros2 bag writes it beside the MCAP file."""
    try:
        path = lab.bags.bag_file(name).parent / "metadata.yaml"
    except Exception as exc:
        raise _error(exc) from exc
    if not path.is_file():
        raise HTTPException(status.HTTP_404_NOT_FOUND, f"{name} has no metadata.yaml")
    return FileResponse(path, media_type="application/yaml", filename=path.name)


@router.post("/players", status_code=status.HTTP_201_CREATED)
async def play(body: PlayRequest, lab: LabDep) -> dict[str, Any]:
    """Publish a bag's messages back onto the bus with their timing (ros2 bag play)."""
    in_folder = lab.settings.bag_dir / body.bag
    path = in_folder if BAG_NAME.match(body.bag) and in_folder.exists() else Path(body.bag)
    try:
        player_id, node = lab.bags.play(path, rate=body.rate, loop=body.loop)
    except Exception as exc:
        raise _error(exc) from exc
    return {"id": player_id, **node.describe()}


@router.get("/players/{player_id}")
async def get_player(player_id: str, lab: LabDep) -> dict[str, Any]:
    try:
        return {"id": player_id, **lab.bags.player(player_id).describe()}
    except Exception as exc:
        raise _error(exc) from exc


@router.delete("/players/{player_id}")
async def stop_player(player_id: str, lab: LabDep) -> dict[str, Any]:
    try:
        return {"id": player_id, **lab.bags.stop_player(player_id).describe()}
    except Exception as exc:
        raise _error(exc) from exc
