"""The class's progress on disk and whose it is: the students not joined since the class server
started, as their files keep them (the instructor's table lists them), and the rule that gives a
world's progress to its own student only.

A world keeps two things on disk under its name: its progress (the state folder) and its
workspace (the class's workspaces folder, the student's code). A join under a name that keeps
either takes them when they are nobody's yet (no owner record: released by the instructor, or kept
before owners were recorded) or when the join presents the token its student was given last (the
join page's cookie, which outlives a restart of the class server though the token no longer grants
anything): server/world/checkpoints/owner.py. A join whose token its world's owner record proves
keeps that token (grants.py): with a class secret, a student's token works again after a restart. Any other join under that name is refused with 409, and
nothing changes. A join that starts a world records its student as the owner at once, so code
written before any progress is theirs too. The instructor releases a student's progress and code
(their owner record is set aside, never removed) for a student who lost their cookie: the next join
under the name takes them.
"""

from __future__ import annotations

import asyncio
import logging
import time
from collections.abc import Callable, Container

from server.classroom.errors import NoSavedProgressError, ProgressOwnedError, WorldJoinedError
from server.world.checkpoints.declared import Checkpoint
from server.world.checkpoints.owner import Owner, OwnerFileError
from server.world.checkpoints.progress import Progress
from server.world.checkpoints.saved_worlds import read_captures, read_saved
from server.world.checkpoints.store import ProgressStore

log = logging.getLogger("classroom")


class SavedStudents:
    """The progress ``store`` keeps, read once at the start (``load``), and the owners of it and of
    the worlds' workspaces (``has_code``: whether a world's workspace holds any file; blocking)."""

    def __init__(
        self,
        store: ProgressStore,
        checkpoints: Callable[[], tuple[Checkpoint, ...]],
        has_code: Callable[[str], bool],
    ) -> None:
        self.store = store
        self._checkpoints = checkpoints
        self._has_code = has_code
        self._saved: dict[str, Progress] = {}  # by world: those not joined since the start

    async def load(self) -> None:
        """Read the state folder's progress (off the loop, bounded: saved_worlds.py)."""
        saved = await asyncio.to_thread(read_saved, self.store.folder, self._checkpoints())
        self._saved = {s.world: s.progress for s in saved}
        if saved:
            log.info(
                "progress of %d student(s) not joined since the start: %s",
                len(saved),
                ", ".join(s.world for s in saved),
            )

    def not_joined(self, live: Container[str]) -> list[tuple[str, Progress]]:
        """The saved students, by world, who have no world now."""
        return [(name, progress) for name, progress in self._saved.items() if name not in live]

    async def with_captures(self, name: str) -> Progress:
        """Saved world ``name``'s progress with its captures (for its report), read off the loop."""
        saved = self._saved[name]
        progress = Progress(saved.checkpoints, saved.student)
        progress.records, progress.answers = dict(saved.records), dict(saved.answers)
        await asyncio.to_thread(read_captures, self.store.world_folder(name), progress)
        return progress

    async def check(self, name: str, student: str, token: str | None) -> bool:
        """A join as ``student`` into world ``name``: ProgressOwnedError unless there is no progress
        nor code on disk under that name, or it is nobody's yet, or ``token`` proves the join is its student's.
        Whether ``token`` proved it (a recorded owner's token)."""
        try:
            owner = await asyncio.to_thread(self._owner_of_saved, name)
        except OwnerFileError as exc:
            raise ProgressOwnedError(
                f"the name {student!r} (world {name!r}) has saved progress or code "
                f"whose owner record cannot be read ({exc}): ask the instructor to release "
                "it, or join under another name"
            ) from None
        if owner is None:  # nothing kept, or nobody's: the token proves its student's only by a record
            return token is not None and await asyncio.to_thread(self._recorded_for, name, token)
        if owner.proven_by(token):
            return True
        raise ProgressOwnedError(
            f"the name {student!r} (world {name!r}) has saved progress or code that belongs to the "
            f"student who joined as {owner.student!r} earlier, and this join does not show it is them: "
            "join again from the browser used then (its cookie shows it), ask the instructor to release "
            "it to you, or join under another name",
        )

    def _owner_of_saved(self, name: str) -> Owner | None:
        """Whose world ``name``'s saved progress and code are; None when it has neither, or they
        are nobody's."""
        kept = self.store.has_progress(name) or self._has_code(name)
        return self.store.owner(name) if kept else None

    def _recorded_for(self, name: str, token: str) -> bool:
        """Whether world ``name``'s owner record, kept or not, is ``token``'s. Blocking."""
        try:
            owner = self.store.owner(name)
        except OwnerFileError:
            return False
        return owner is not None and owner.proven_by(token)

    async def claim(self, name: str, student: str, token: str) -> None:
        """``student`` joined world ``name`` with ``token``: its progress is theirs from now on."""
        self._saved.pop(name, None)  # listed from its world from now on
        try:
            await asyncio.to_thread(self.store.claim, name, Owner.of(student, token))
        except OSError as exc:  # they work all the same; after a restart the instructor releases it
            log.warning("world %s: its owner is not recorded (%s)", name, exc)

    async def release(self, name: str, live: Container[str]) -> str:
        """Set aside world ``name``'s owner record: the next join under its name takes its progress.
        The student it belonged to; WorldJoinedError for a world joined now, NoSavedProgressError for
        one with no saved progress."""
        if name in live:
            raise WorldJoinedError(f"world {name!r} is joined now: its progress is its student's")
        try:
            owner = await asyncio.to_thread(self.store.owner, name)
        except OwnerFileError:
            owner = None  # set aside all the same
        stamp = time.strftime("%Y%m%dT%H%M%SZ", time.gmtime())
        aside = await asyncio.to_thread(self.store.release, name, stamp)
        if aside is None:
            raise NoSavedProgressError(f"world {name!r} has no saved progress with an owner to release")
        log.info("progress of world %s released (its owner record is now %s)", name, aside.name)
        saved = self._saved.get(name)
        if owner is not None:
            return owner.student
        return (saved.student if saved is not None else None) or name
