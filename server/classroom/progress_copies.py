"""The class server's copy of the progress of worlds its world workers keep in folders of their own.

A worker that shares the class server's state folder (one on this machine, or a shared mount; it
reads the same mark there, server/services/workspace/class_mark.py) keeps each world's progress where the
class server and every other such worker read it. A worker with a folder of its own would take a
world's ticks and answers with it when it goes, so at every round of hellos the class server asks
each such worker, in one call, for the progress of its worlds that changed since the copy it has
(server/world/checkpoints/handover.py) and writes it to its own folder; when a world then starts on such
a worker (a move, a returning student), the worker is handed that copy with the world. A world
that moves here, or to a worker that shares the folder, reads the copy there. What a world changed
after the last round before its worker went is lost (at most one round, WATCH_PERIOD_S).
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Mapping
from typing import Any

from server.classroom.errors import ClassroomError
from server.classroom.remote_worlds import on_workers
from server.classroom.workers import WorkerDirectory, WorkerRef
from server.classroom.world import World
from server.services.workspace.class_mark import leave_mark
from server.world.checkpoints.declared import Checkpoint
from server.world.checkpoints.handover import from_wire, to_wire
from server.world.checkpoints.saved import SavedProgressError
from server.world.checkpoints.store import ProgressStore

log = logging.getLogger("classroom")
ASK_TIMEOUT_S = 10.0  # a round's ask: the worlds' changed progress, captures included
PROGRESS_PATH = "/api/classroom/checkpoints/progress"


class ProgressCopies:
    """The copies, in ``store`` (the class server's own progress folder)."""

    def __init__(self, store: ProgressStore, checkpoints: tuple[Checkpoint, ...]) -> None:
        self.store = store
        self.checkpoints = checkpoints
        self.mark: str | None = None  # the progress folder's mark, once left there
        self._tags: dict[str, str] = {}  # world → the tag of the copy written

    def leave_mark(self) -> None:
        """Mark the progress folder (blocking): a worker that reads this mark shares it."""
        self.mark = leave_mark(self.store.folder)

    def shares(self, ref: WorkerRef) -> bool:
        return self.mark is not None and ref.progress_mark == self.mark

    async def refresh(
        self, workers: WorkerDirectory, worlds: Mapping[str, World], answered: list[WorkerRef]
    ) -> None:
        """Ask each worker that answered this round, and keeps progress in its own folder, for
        what changed in its worlds; copy it. A worker that cannot answer is asked again next round."""
        answering = {ref.id for ref in answered}
        asked = [
            (ref, names)
            for ref, names in on_workers(worlds).values()
            if ref.id in answering and not self.shares(ref)
        ]
        await asyncio.gather(*(self._refresh_one(workers, worlds, ref, names) for ref, names in asked))

    async def _refresh_one(
        self, workers: WorkerDirectory, worlds: Mapping[str, World], ref: WorkerRef, names: list[str]
    ) -> None:
        known = {name: self._tags[name] for name in names if name in self._tags}
        try:
            reply = await asyncio.wait_for(
                workers.checked(ref, "POST", PROGRESS_PATH, body={"known": known}), ASK_TIMEOUT_S
            )
        except (ClassroomError, TimeoutError) as exc:
            log.warning(
                "progress of world worker %s's worlds not copied this round: %s", ref.id, exc or "timed out"
            )
            return
        changed = reply.get("worlds") if isinstance(reply, dict) else None
        if not isinstance(changed, dict):
            log.warning("world worker %s answered with no progress of its worlds", ref.id)
            return
        for name, item in changed.items():
            if name not in names or not isinstance(item, dict) or not isinstance(item.get("tag"), str):
                continue  # not a world of this class's on that worker
            world = worlds.get(name)
            if world is None or world.worker is None or world.worker.id != ref.id:
                continue  # removed or moved while it answered: its copy is no longer that worker's
            try:
                snapshot = from_wire(item.get("progress"), self.checkpoints)
                await asyncio.to_thread(self.store.put, name, snapshot)
            except (SavedProgressError, OSError, ValueError) as exc:
                log.warning("progress of world %s from world worker %s not copied: %s", name, ref.id, exc)
                continue
            self._tags[name] = item["tag"]

    async def handover(self, ref: WorkerRef, world: str) -> dict[str, Any] | None:
        """The copy of ``world``'s progress to hand worker ``ref`` with the world, when it keeps
        progress in a folder of its own and there is a copy."""
        if self.shares(ref):
            return None
        snapshot = await asyncio.to_thread(self.store.snapshot, world, self.checkpoints)
        return to_wire(snapshot) if snapshot is not None else None

    def forget(self, world: str) -> None:
        """The world is gone, or starts again: the next round copies its progress whole."""
        self._tags.pop(world, None)
