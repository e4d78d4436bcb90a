"""REST: record and replay like ``ros2 bag`` (record, stop, list, download, play, stop playing).

Bags are written into the server's bag folder (``--bag-dir``) under a plain name; the download
serves the MCAP file that Foxglove, Lichtblick and ``ros2 bag info`` open.
"""

from __future__ import annotations

import asyncio
import shutil

from fastapi import APIRouter, HTTPException, status
from fastapi.responses import FileResponse
from pydantic import TypeAdapter

from api.deps import LabDep
from api.protocol.bag import BagDeleted, PlayerOut, PlayRequest, RecordingOut, RecordRequest, StoredBag
from api.protocol.responses import NOT_FOUND, TOO_MANY, TYPE_CONFLICT, UNPROCESSABLE, responses

# Handlers are ``async def``: the bus belongs to the event loop (see api/routes/publishers.py).
# Errors (server/peripherals/bag/errors.py) are mapped to statuses once, in api/errors.py.
router = APIRouter(prefix="/api/bag", tags=["bag"], responses=responses())
BAGS = TypeAdapter(list[RecordingOut | StoredBag])


@router.post(
    "/recordings",
    status_code=status.HTTP_201_CREATED,
    responses=responses(TYPE_CONFLICT, TOO_MANY, body=True),
)
async def record(body: RecordRequest, lab: LabDep) -> RecordingOut:
    """Start recording the named topics (or all of them) into a new bag (ros2 bag record)."""
    return RecordingOut.model_validate(
        lab.bags.record(body.topics, all_topics=body.all, name=body.name).describe()
    )


@router.get("/recordings")
async def list_recordings(lab: LabDep) -> list[RecordingOut | StoredBag]:
    """This run's recordings (with counts) and the older bags in the bag folder."""
    return BAGS.validate_python(lab.bags.list_bags())


@router.post("/recordings/{name}/stop", responses=responses(NOT_FOUND, UNPROCESSABLE))
async def stop_recording(name: str, lab: LabDep) -> RecordingOut:
    """Stop a recording (Ctrl-C on ros2 bag record); the bag is complete (MCAP summary,
    metadata.yaml) when this returns, and stays in the bag folder. Stopping a stopped one is a no-op."""
    recording = lab.bags.detach_recording(name)
    await asyncio.to_thread(recording.writer.close)  # the disk, not the loop, waits
    return RecordingOut.model_validate(recording.describe())


@router.delete("/recordings/{name}", responses=responses(NOT_FOUND, UNPROCESSABLE))
async def delete_bag(name: str, lab: LabDep) -> BagDeleted:
    """Delete a bag from the bag folder (a recording is stopped first)."""
    folder, recording = lab.bags.detach_bag(name)
    if recording is not None:
        await asyncio.to_thread(recording.writer.close)
    await asyncio.to_thread(shutil.rmtree, folder, True)
    return BagDeleted(name=name, deleted=True)


@router.get(
    "/recordings/{name}/download",
    response_class=FileResponse,
    responses=responses(NOT_FOUND, TYPE_CONFLICT, UNPROCESSABLE),
)
async def download(name: str, lab: LabDep) -> FileResponse:
    """The bag's MCAP file (409 while it is still being recorded)."""
    path = lab.bags.bag_file(name)
    return FileResponse(path, media_type="application/octet-stream", filename=path.name)


@router.get(
    "/recordings/{name}/metadata.yaml",
    response_class=FileResponse,
    responses=responses(NOT_FOUND, TYPE_CONFLICT, UNPROCESSABLE),
)
async def metadata(name: str, lab: LabDep) -> FileResponse:
    """The bag's metadata.yaml, as ros2 bag writes it beside the MCAP file."""
    path = lab.bags.bag_file(name).parent / "metadata.yaml"
    if not path.is_file():
        raise HTTPException(status.HTTP_404_NOT_FOUND, f"{name} has no metadata.yaml")
    return FileResponse(path, media_type="application/yaml", filename=path.name)


@router.post(
    "/players", status_code=status.HTTP_201_CREATED, responses=responses(NOT_FOUND, TOO_MANY, body=True)
)
async def play(body: PlayRequest, lab: LabDep) -> PlayerOut:
    """Publish a bag's messages back onto the bus with their timing (ros2 bag play)."""
    path = lab.bags.bag_to_play(body.bag, confined=lab.settings.confines_paths)
    player_id, node = lab.bags.play(path, rate=body.rate, loop=body.loop)
    return PlayerOut.model_validate({"id": player_id, **node.describe()})


@router.get("/players/{player_id}", responses=responses(NOT_FOUND))
async def get_player(player_id: str, lab: LabDep) -> PlayerOut:
    return PlayerOut.model_validate({"id": player_id, **lab.bags.player(player_id).describe()})


@router.delete("/players/{player_id}", responses=responses(NOT_FOUND))
async def stop_player(player_id: str, lab: LabDep) -> PlayerOut:
    return PlayerOut.model_validate({"id": player_id, **lab.bags.stop_player(player_id).describe()})
