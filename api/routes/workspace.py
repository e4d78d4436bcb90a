"""REST: the student's workspace as files: its tree, each file's text with a version (ETag) so a
stale save is refused (412), new packages as ``ros2 pkg create`` writes them, the lab's templates,
and the whole workspace as a zip, down and up.

The workspace is the lab's folder (``settings.lab.workspace``: ``./workspace`` on a single lab,
the world's own folder on a class server), reached with the caller's token as every route is.
Paths are confined to it (server/services/workspace/paths.py), and opened one folder at a time, never
through a symbolic link (server/services/workspace/handles.py); errors map in api/errors.py. The disk is
read and written in a worker thread (a tree is a walk of up to thousands of ``stat`` calls), never
on the loop that runs the labs. A zip is built in a temporary file and sent from there in chunks:
a workspace a node filled may hold far more than the API would ever write.
"""

from __future__ import annotations

import asyncio
import functools
import os
import weakref
from collections.abc import AsyncIterator, Mapping
from typing import IO, Annotated, Any

from fastapi import APIRouter, Header, Query, Request, Response, status
from fastapi.responses import StreamingResponse

from api.deps import LabDep
from api.protocol.responses import NOT_FOUND, TYPE_CONFLICT, UNPROCESSABLE, responses
from api.protocol.workspace import (
    Deleted,
    FileText,
    PackageCreated,
    PackageRequest,
    Renamed,
    RenameRequest,
    Saved,
    SaveRequest,
    Template,
    WorkspaceEntry,
    WorkspaceTree,
    Written,
)
from server.packages.templates import PackageSpec
from server.services.workspace.archive import packed, replace, unpack
from server.services.workspace.errors import NoWorkspaceError
from server.services.workspace.files import WorkspaceFiles
from server.services.workspace.package_create import create_package
from server.services.workspace.templates import TEMPLATES
from server.services.workspace.tree import Tree
from server.world.lab import Lab

PREFIX = "/api/workspace/"
router = APIRouter(prefix="/api/workspace", tags=["workspace"])
_files: weakref.WeakKeyDictionary[Lab, WorkspaceFiles] = weakref.WeakKeyDictionary()
PRECONDITION = 412
TOO_LARGE = 413
NOT_TEXT = 415
ZIP = "application/zip"
ZIP_CHUNK = 256 * 1024  # bytes read from the zip's temporary file per send


def files_of(lab: Lab) -> WorkspaceFiles:
    """The lab's workspace (one object per lab, so its writes share one lock)."""
    root = lab.settings.lab.workspace
    if root is None:
        raise NoWorkspaceError("this lab has no workspace folder")
    files = _files.get(lab)
    if files is None or files.root != root:
        files = _files[lab] = WorkspaceFiles(root, lab.settings.workspace)
    return files


def tree_body(tree: Tree) -> WorkspaceTree:
    entries = [WorkspaceEntry(path=e.path, kind=e.kind, size=e.size, etag=e.etag) for e in tree.entries]
    return WorkspaceTree(
        version=tree.version, entries=entries, too_deep=tree.too_deep, too_deep_example=tree.too_deep_example
    )


async def zip_response(sources: Mapping[str, WorkspaceFiles], filename: str) -> StreamingResponse:
    """The workspaces' zip (``archive.packed``), built in a worker thread and sent in chunks."""
    out = await asyncio.to_thread(packed, sources)
    size = os.fstat(out.fileno()).st_size
    headers = {"Content-Disposition": f'attachment; filename="{filename}"', "Content-Length": str(size)}
    return StreamingResponse(_chunks(out), media_type=ZIP, headers=headers)


async def _chunks(out: IO[bytes]) -> AsyncIterator[bytes]:
    try:
        while chunk := await asyncio.to_thread(out.read, ZIP_CHUNK):
            yield chunk
    finally:
        out.close()  # the temporary file goes with it


def etag_value(header: str | None) -> str | None:
    """An ``If-Match`` value as the etag it names (quoted or not, weak or not)."""
    if header is None:
        return None
    return header.strip().removeprefix("W/").strip('"')


FILE_ERRORS = responses(NOT_FOUND, UNPROCESSABLE, NOT_TEXT, TOO_LARGE)
WRITE_ERRORS = responses(NOT_FOUND, TYPE_CONFLICT, PRECONDITION, NOT_TEXT, TOO_LARGE, body=True)
CREATED: dict[int | str, dict[str, Any]] = {201: {"description": "a new file was created"}}


@router.get("/files", responses=responses(NOT_FOUND))
async def tree(lab: LabDep) -> WorkspaceTree:
    """Every file and folder, sorted by path; ``version`` changes with any change in the tree.
    Entries deeper than the depth limit are counted in ``too_deep``, not listed."""
    return tree_body(await asyncio.to_thread(files_of(lab).tree))


@router.get("/files/{path:path}", responses=FILE_ERRORS)
async def read(path: str, lab: LabDep, response: Response) -> FileText:
    """A file's text and version (also in the ``ETag`` header)."""
    found = await asyncio.to_thread(files_of(lab).read, path)
    response.headers["ETag"] = f'"{found.etag}"'
    return FileText(path=found.path, text=found.text, etag=found.etag)


@router.put("/files/{path:path}", responses={**CREATED, **WRITE_ERRORS})
async def save(
    path: str,
    body: SaveRequest,
    lab: LabDep,
    response: Response,
    if_match: Annotated[str | None, Header()] = None,
    if_none_match: Annotated[str | None, Header()] = None,
) -> Saved:
    """Save a file: over the version ``If-Match`` names, or with ``If-None-Match: *`` only a new
    one (412 otherwise, with the current etag); missing folders are made. 201 when created."""
    create_only = (if_none_match or "").strip() == "*"
    write = functools.partial(files_of(lab).write, if_match=etag_value(if_match), create_only=create_only)
    saved = await asyncio.to_thread(write, path, body.text)
    if saved.created:
        response.status_code = status.HTTP_201_CREATED
    response.headers["ETag"] = f'"{saved.etag}"'
    return Saved(path=saved.path, etag=saved.etag, size=saved.size)


@router.delete("/files/{path:path}", responses=responses(NOT_FOUND, UNPROCESSABLE, PRECONDITION))
async def delete(path: str, lab: LabDep, if_match: Annotated[str | None, Header()] = None) -> Deleted:
    """Remove a file, or a folder with everything in it; how many files went."""
    delete = functools.partial(files_of(lab).delete, if_match=etag_value(if_match))
    return Deleted(path=path, deleted=await asyncio.to_thread(delete, path))


@router.post("/rename", responses=responses(NOT_FOUND, TYPE_CONFLICT, body=True))
async def rename(body: RenameRequest, lab: LabDep) -> Renamed:
    """Move a file or folder to a free path (409 when the target exists)."""
    return Renamed(path=await asyncio.to_thread(files_of(lab).rename, body.source, body.target))


@router.post(
    "/packages",
    status_code=status.HTTP_201_CREATED,
    responses=responses(NOT_FOUND, TYPE_CONFLICT, TOO_LARGE, body=True),
)
async def new_package(body: PackageRequest, lab: LabDep) -> PackageCreated:
    """A package in ``src/<name>`` with the files ``ros2 pkg create`` writes (409 if taken)."""
    spec = PackageSpec(
        name=body.name,
        build_type=body.build_type,
        node_name=body.node_name,
        dependencies=list(body.dependencies),
        description=body.description or PackageSpec.description,
        license=body.license or PackageSpec.license,
        maintainer_name="student",
        maintainer_email="student@todo.todo",
    )
    created = await asyncio.to_thread(create_package, files_of(lab), spec)
    return PackageCreated(name=created.name, path=created.path, files=created.files)


@router.get("/templates")
async def templates(_lab: LabDep) -> list[Template]:
    """The lab's starting files, with ``# TODO`` where the student's code goes."""
    return [Template.model_validate(t.describe()) for t in TEMPLATES]


@router.get(
    "/archive", response_class=Response, responses={200: {"content": {ZIP: {}}}, **responses(NOT_FOUND)}
)
async def download(lab: LabDep) -> Response:
    """The workspace's files in one zip (every file the tree lists, whatever its size)."""
    files = files_of(lab)
    return await zip_response({"": files}, f"{files.root.name}.zip")


@router.post(
    "/archive",
    openapi_extra={
        # The zip's bytes as the body, sent as application/zip or any other type: the document
        # names the generic binary type, which every client (and schemathesis) can send.
        "requestBody": {
            "required": True,
            "description": "the zip's bytes (Content-Type application/zip or application/octet-stream)",
            "content": {"application/octet-stream": {"schema": {"type": "string", "format": "binary"}}},
        }
    },
    responses=responses(NOT_FOUND, TOO_LARGE, NOT_TEXT, body=True),
)
async def upload(
    request: Request, lab: LabDep, replace_all: Annotated[bool, Query(alias="replace")] = False
) -> Written:
    """Write a zip's files into the workspace: all of them, or (one entry refused) none. With
    ``replace=true`` the workspace then holds the zip's files only: every other file goes."""
    files = files_of(lab)
    data = await request.body()
    return Written(written=await asyncio.to_thread(replace if replace_all else unpack, files, data))
