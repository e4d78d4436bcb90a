"""The worlds whose progress a class server's state folder holds, read once as it starts: the
instructor's table lists each of their students until they join again (their checkpoints as their
files keep them), and the class's zip holds their reports.

Reading is bounded: at most ``MAX_SAVED_WORLDS`` folders, each progress file within saved.py's
limit, and no captures (read_captures reads one world's when its report is made). A file that
cannot be read is logged and left as it is: the world's own start sets it aside (store.py).
"""

from __future__ import annotations

import logging
import os
import re
from dataclasses import dataclass
from pathlib import Path

from server.world.checkpoints.declared import Checkpoint
from server.world.checkpoints.owner import OwnerFileError, read_owner
from server.world.checkpoints.progress import Progress
from server.world.checkpoints.saved import MAX_FILE_BYTES, SavedProgressError, decode
from server.world.checkpoints.store import PROGRESS_FILE, read_capture

log = logging.getLogger("checkpoints")
MAX_SAVED_WORLDS = 1000
_CLASS_WORLD = re.compile(r"[a-z][a-z0-9_]{0,31}")  # a name world.world_name makes (not the lab's "_lab")


@dataclass
class SavedWorld:
    world: str
    progress: Progress  # its student: the owner record's name, else the world's


def read_saved(
    folder: Path, checkpoints: tuple[Checkpoint, ...], limit: int = MAX_SAVED_WORLDS
) -> list[SavedWorld]:
    """Every class world in ``folder`` (a state folder's ``progress/``) with a progress file, by
    name; at most ``limit`` folders are looked at. Blocking: call it off the loop."""
    names: list[str] = []
    try:
        with os.scandir(folder) as entries:
            for entry in entries:
                if _CLASS_WORLD.fullmatch(entry.name) and entry.is_dir(follow_symlinks=False):
                    if len(names) == limit:
                        log.warning(
                            "progress: more than %d worlds in %s; the class table lists %d of them",
                            limit,
                            folder,
                            limit,
                        )
                        break
                    names.append(entry.name)
    except FileNotFoundError:
        return []
    except OSError as exc:
        log.warning("progress: cannot list %s (%s): the class table lists no saved progress", folder, exc)
        return []
    out = []
    for name in sorted(names):
        progress = _read(folder / name, checkpoints)
        if progress is not None:
            out.append(SavedWorld(name, progress))
    return out


def _read(world_folder: Path, checkpoints: tuple[Checkpoint, ...]) -> Progress | None:
    path = world_folder / PROGRESS_FILE
    try:
        if path.stat().st_size > MAX_FILE_BYTES:
            log.warning("progress: %s is larger than %d bytes: not listed", path, MAX_FILE_BYTES)
            return None
        raw = path.read_bytes()
    except FileNotFoundError:
        return None
    except OSError as exc:
        log.warning("progress: cannot read %s (%s): not listed", path, exc)
        return None
    try:
        owner = read_owner(world_folder)
    except OwnerFileError as exc:
        log.warning("progress of world %s: %s", world_folder.name, exc)
        owner = None
    progress = Progress(checkpoints, owner.student if owner is not None else world_folder.name)
    try:
        decode(raw, progress)
    except SavedProgressError as exc:
        log.warning("progress: %s is not a progress file (%s): not listed", path, exc)
        return None
    return progress


def read_captures(world_folder: Path, progress: Progress) -> None:
    """Put the captures ``world_folder`` holds into ``progress``. Blocking."""
    for checkpoint in progress.checkpoints:
        png = read_capture(world_folder, checkpoint.name)
        if png is not None:
            progress.captures[checkpoint.name] = png
