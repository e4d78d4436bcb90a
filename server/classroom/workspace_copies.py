"""The class server's copy of the workspaces of worlds on world workers that keep them in folders
of their own.

A worker that shares the class's workspaces folder (the same mark, server/services/workspace/class_mark.py)
works in the class's own copy of each world's files. One with a folder of its own (another
machine, no shared mount) serves and runs its worlds' files from there, so the class server keeps
them in step both ways, as it does the worlds' progress (progress_copies.py):

- **Handed over** when a world starts on such a worker (a new student, a move, a returning
  student): the class's copy goes with it and replaces whatever that worker's folder held for the
  world, before its student can reach it there. A hand-over that fails fails the start (the world
  is ended there), so an empty or stale folder never overwrites the class's copy, and a copy
  handed late never overwrites a student's saves.
- **Copied back** at every round of hellos: each such world's tree version is asked for (one
  small call), and when it changed the world's files come back as a zip and replace the class's
  copy (the instructor's reads, the download of every workspace, a later move read that).

What a student saved after the last round before their worker went is lost (at most one round,
WATCH_PERIOD_S), as for progress.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Mapping
from pathlib import Path

from server.classroom.errors import ClassroomError, WorkerFailedError
from server.classroom.workers import WorkerDirectory, WorkerRef
from server.classroom.world import World
from server.host.settings import WorkspaceLimits
from server.services.workspace.archive import pack, replace
from server.services.workspace.class_mark import leave_mark
from server.services.workspace.errors import WorkspaceFileError
from server.services.workspace.files import WorkspaceFiles
from server.services.workspace.location import world_workspace

log = logging.getLogger("classroom")
TREE_PATH = "/api/workspace/files"
ARCHIVE_PATH = "/api/workspace/archive"


class WorkspaceCopies:
    """The copies, in ``folder`` (the class's workspaces folder), for the workers that do not work
    in that folder themselves (``shares``: the same mark, left by ``leave_mark``)."""

    def __init__(self, folder: Path, limits: WorkspaceLimits) -> None:
        self.folder = folder
        self.limits = limits
        self.mark: str | None = None  # the folder's mark, once left
        self._handed: dict[str, str] = {}  # world → the worker its files were handed to
        self._copied: dict[str, str] = {}  # world → the version of that worker's tree copied back

    def leave_mark(self) -> None:
        """Mark the workspaces folder (blocking): a worker that reads this mark shares it
        (server/services/workspace/class_mark.py)."""
        self.mark = leave_mark(self.folder)

    def shares(self, ref: WorkerRef) -> bool:
        """Whether world worker ``ref`` works in this class's workspaces folder (the same mark)."""
        return self.mark is not None and ref.workspaces_mark == self.mark

    def files(self, world: str) -> WorkspaceFiles:
        return WorkspaceFiles(world_workspace(self.folder, world), self.limits)

    async def hand_over(self, workers: WorkerDirectory, ref: WorkerRef, world: str) -> None:
        """Give ``world``, started on ``ref``, the class's copy of its files (nothing to do on a
        worker that shares the folder); WorkerFailedError if the worker did not take them."""
        if self.shares(ref):
            return
        try:  # no more than the worker takes in an upload: a larger zip is refused there anyway
            data = await asyncio.to_thread(pack, self.files(world), self.limits.max_body_bytes)
        except (OSError, WorkspaceFileError) as exc:
            raise WorkerFailedError(f"world {world!r}'s files could not be read: {exc}") from None
        reply = await workers.call(ref, "POST", f"{ARCHIVE_PATH}?replace=true", world=world, content=data)
        if reply.status_code != 200:
            raise WorkerFailedError(
                f"world worker {ref.id!r} did not take world {world!r}'s files: "
                f"{reply.status_code} {reply.text[:200]}"
            )
        self._handed[world] = ref.id
        self._copied.pop(world, None)

    async def refresh(
        self, workers: WorkerDirectory, worlds: Mapping[str, World], answered: list[WorkerRef]
    ) -> None:
        """One round: each world handed to a worker that answered (one that keeps its own folder)
        is copied back if its tree changed."""
        answering = {ref.id for ref in answered}
        for name, world in list(worlds.items()):
            ref = world.worker
            if ref is None or ref.id not in answering or world.lost is not None:
                continue
            if self._handed.get(name) != ref.id:  # here, on a worker that shares the folder, or moving
                continue
            try:
                await self._copy_back(workers, ref, name)
            except (ClassroomError, WorkspaceFileError, OSError) as exc:
                log.warning("world %s's files not copied from world worker %s: %s", name, ref.id, exc)
        for name in set(self._handed) - set(worlds):  # removed: forget it
            self._handed.pop(name, None)
            self._copied.pop(name, None)

    async def _copy_back(self, workers: WorkerDirectory, ref: WorkerRef, name: str) -> None:
        tree = await workers.checked(ref, "GET", TREE_PATH, world=name)
        version = tree.get("version") if isinstance(tree, dict) else None
        if not isinstance(version, str) or version == self._copied.get(name):
            return
        reply = await workers.call(ref, "GET", ARCHIVE_PATH, world=name)
        if reply.status_code != 200:
            raise WorkerFailedError(f"the archive: {reply.status_code} {reply.text[:200]}")
        if self._handed.get(name) != ref.id:  # it moved while its files were on their way
            return
        await asyncio.to_thread(replace, self.files(name), reply.content)
        self._copied[name] = version
