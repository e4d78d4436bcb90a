"""The instructor's view of the students' workspaces on a class server: any world's tree and
files, read-only (the shapes of ``/api/workspace/files``), and every workspace in one zip with a
folder per world. A world on a world worker is read through its worker, as the instructor."""

from __future__ import annotations

import asyncio
import io
import zipfile
from typing import Any

from fastapi import APIRouter, Response
from fastapi.responses import JSONResponse

from server.classroom import Classroom, ClassroomError, ClassServer, World
from server.workspace.archive import add_to

from .classroom import ClassroomDep, InstructorDep
from .responses import BAD_GATEWAY, FORBIDDEN, NOT_FOUND, UNAUTHORIZED, UNPROCESSABLE, responses
from .workspace import ZIP, files_of, tree_body

router = APIRouter(prefix="/api/classroom", tags=["classroom"])
REFUSED = responses(UNAUTHORIZED, FORBIDDEN, NOT_FOUND, BAD_GATEWAY)
FILE_REFUSED = responses(UNAUTHORIZED, FORBIDDEN, NOT_FOUND, BAD_GATEWAY, UNPROCESSABLE, 413, 415)


async def _on_worker(classroom: Classroom, world: World, path: str) -> Response:
    """The world's worker's answer to a GET of ``path`` for this world, passed on."""
    if not isinstance(classroom, ClassServer) or classroom.workers is None or world.worker is None:
        raise ClassroomError(404, f"world {world.name!r} runs in another process: nothing here for it")
    reply = await classroom.workers.call(world.worker, "GET", path, world=world.name)
    media = reply.headers.get("content-type", "application/json")
    return Response(reply.content, status_code=reply.status_code, media_type=media)


@router.get("/worlds/{name}/workspace/files", responses=REFUSED)
async def world_tree(name: str, _: InstructorDep, classroom: ClassroomDep) -> Any:
    """A student's workspace tree, as ``GET /api/workspace/files`` gives it to them."""
    world = classroom.get(name)
    if world.lab is None:
        return await _on_worker(classroom, world, "/api/workspace/files")
    return tree_body(await asyncio.to_thread(files_of(world.lab).tree))


@router.get("/worlds/{name}/workspace/files/{path:path}", responses=FILE_REFUSED)
async def world_file(name: str, path: str, _: InstructorDep, classroom: ClassroomDep) -> Any:
    """One file of a student's workspace, read-only."""
    world = classroom.get(name)
    if world.lab is None:
        return await _on_worker(classroom, world, f"/api/workspace/files/{path}")
    found = await asyncio.to_thread(files_of(world.lab).read, path)
    return JSONResponse(
        {"path": found.path, "text": found.text, "etag": found.etag}, headers={"ETag": f'"{found.etag}"'}
    )


@router.get(
    "/workspaces/archive",
    response_class=Response,
    responses={200: {"content": {ZIP: {}}}, **responses(UNAUTHORIZED, FORBIDDEN, NOT_FOUND, BAD_GATEWAY)},
)
async def all_workspaces(_: InstructorDep, classroom: ClassroomDep) -> Response:
    """Every student's workspace in one zip: a folder per world (``ada/src/...``)."""
    parts: dict[str, bytes] = {}
    for world in list(classroom.worlds.values()):
        if world.lab is None:
            reply = await _on_worker(classroom, world, "/api/workspace/archive")
            if reply.status_code != 200:
                raise ClassroomError(502, f"world {world.name!r}: its worker did not give its workspace")
            parts[world.name] = bytes(reply.body)
    data = await asyncio.to_thread(_pack_all, classroom, parts)
    return Response(
        data, media_type=ZIP, headers={"Content-Disposition": 'attachment; filename="workspaces.zip"'}
    )


def _pack_all(classroom: Classroom, on_workers: dict[str, bytes]) -> bytes:
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as archive:
        for world in list(classroom.worlds.values()):
            if world.lab is not None:
                add_to(archive, files_of(world.lab), f"{world.name}/")
            elif world.name in on_workers:
                with zipfile.ZipFile(io.BytesIO(on_workers[world.name])) as theirs:
                    for info in theirs.infolist():
                        archive.writestr(f"{world.name}/{info.filename}", theirs.read(info))
    return buffer.getvalue()
