"""The instructor's view of the students' workspaces on a class server: any world's tree and
files, read-only (the shapes of ``/api/workspace/files``), and every workspace in one zip with a
folder per world, built in a temporary file and sent from there as the student's own zip is.

Every world's workspace is the folder of its name in the class's ``workspaces_dir``, wherever the
world runs: a world worker serves a workspace only when it shares that folder (api/middleware/world_proxy.py),
so the class server reads each one from its own disk, also while the world's worker is gone."""

from __future__ import annotations

import asyncio

from fastapi import APIRouter, Response

from api.protocol.responses import FORBIDDEN, NOT_FOUND, UNAUTHORIZED, UNPROCESSABLE, responses
from api.protocol.workspace import FileText, WorkspaceTree
from api.routes.classroom import ClassroomDep, InstructorDep
from api.routes.workspace import ZIP, files_of, tree_body, zip_response
from server.classroom import Classroom, World
from server.services.workspace.files import WorkspaceFiles
from server.services.workspace.location import world_workspace

router = APIRouter(prefix="/api/classroom", tags=["classroom"])
REFUSED = responses(UNAUTHORIZED, FORBIDDEN, NOT_FOUND)
FILE_REFUSED = responses(UNAUTHORIZED, FORBIDDEN, NOT_FOUND, UNPROCESSABLE, 413, 415)


def workspace_of(classroom: Classroom, world: World) -> WorkspaceFiles:
    """The world's workspace: its lab's when it runs here, else its folder in the class's."""
    if world.lab is not None:
        return files_of(world.lab)
    folder = world_workspace(classroom.class_settings.workspaces_dir, world.name)
    return WorkspaceFiles(folder, classroom.settings.workspace)


@router.get("/worlds/{name}/workspace/files", responses=REFUSED)
async def world_tree(name: str, _: InstructorDep, classroom: ClassroomDep) -> WorkspaceTree:
    """A student's workspace tree, as ``GET /api/workspace/files`` gives it to them."""
    files = workspace_of(classroom, classroom.get(name))
    return tree_body(await asyncio.to_thread(files.tree))


@router.get("/worlds/{name}/workspace/files/{path:path}", responses=FILE_REFUSED)
async def world_file(
    name: str, path: str, _: InstructorDep, classroom: ClassroomDep, response: Response
) -> FileText:
    """One file of a student's workspace, read-only (its version also in the ``ETag`` header)."""
    files = workspace_of(classroom, classroom.get(name))
    found = await asyncio.to_thread(files.read, path)
    response.headers["ETag"] = f'"{found.etag}"'
    return FileText(path=found.path, text=found.text, etag=found.etag)


@router.get(
    "/workspaces/archive",
    response_class=Response,
    responses={200: {"content": {ZIP: {}}}, **responses(UNAUTHORIZED, FORBIDDEN)},
)
async def all_workspaces(_: InstructorDep, classroom: ClassroomDep) -> Response:
    """Every student's workspace in one zip: a folder per world (``ada/src/...``)."""
    workspaces = {f"{w.name}/": workspace_of(classroom, w) for w in list(classroom.worlds.values())}
    return await zip_response(workspaces, "workspaces.zip")
