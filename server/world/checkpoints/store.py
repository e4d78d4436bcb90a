"""Each world's progress on disk, so a restart of the server loses no student's ticks and answers.

One folder per world in ``<state_dir>/progress/``: ``progress.json`` (saved.py), a
``<checkpoint>.png`` per capture and, on a class server, ``student.json``: whose it is (owner.py).
Every file is written whole to a temporary file and moved into place (``os.replace``), so a crash
leaves the old file or the new one, never half of one.

Writing never happens where the change does (a check met in the sim loop's drain, an answer in a
route): a change queues a copy of the progress (one per world, the newest wins) and one thread of
the store's writes it. ``open`` reads a world's files when it starts; a file that cannot be read is
logged by name, set aside as ``progress.json.corrupt`` and the world starts with no progress.
"""

from __future__ import annotations

import contextlib
import logging
import os
import re
import tempfile
import threading
from pathlib import Path

from server.services.workspace.location import remove_folder
from server.world.checkpoints.declared import Checkpoint
from server.world.checkpoints.owner import OWNER_FILE, Owner, read_owner
from server.world.checkpoints.progress import MAX_CAPTURE_BYTES, Progress
from server.world.checkpoints.saved import SavedProgressError, Snapshot, capture_ok, decode, encode

log = logging.getLogger("checkpoints")
PROGRESS_DIR = "progress"  # in the server's state folder
PROGRESS_FILE = "progress.json"
SINGLE_LAB = "_lab"  # a lab alone (no class world can take this name: theirs start with a letter or digit)
CLOSE_WAIT_S = 10.0
_NAME = re.compile(r"[A-Za-z0-9_][A-Za-z0-9_-]{0,63}")


class ProgressStore:
    """The progress files of the worlds in ``folder``, and the thread that writes them."""

    def __init__(self, folder: Path) -> None:
        self.folder = folder
        self._cond = threading.Condition()
        self._io = threading.Lock()  # one world's files at a time: a write, a read or a removal
        self._live: dict[str, object] = {}  # world → the key of its Progress now (open() made it)
        self._pending: dict[str, tuple[object, Snapshot]] = {}
        self._written: dict[str, dict[str, bytes]] = {}  # world → the captures on disk, by checkpoint
        self._busy = False
        self._closing = False
        self._thread: threading.Thread | None = None

    @classmethod
    def in_state_dir(cls, state_dir: Path) -> ProgressStore:
        return cls(state_dir / PROGRESS_DIR)

    def world_folder(self, world: str) -> Path:
        """The folder of ``world``'s files; ValueError for a name that is not one plain name."""
        if not _NAME.fullmatch(world):
            raise ValueError(f"not a world's name: {world!r}")
        return self.folder / world

    # -- a world starts, ends, is removed ------------------------------------------------------
    def open(self, world: str, checkpoints: tuple[Checkpoint, ...]) -> Progress:
        """``world``'s progress as its files keep it (none: empty), saved from now on when it
        changes. Blocking (it reads files): call it off the loop, or before the loop runs."""
        folder = self.world_folder(world)
        progress = Progress(checkpoints)
        with self._io:
            self._read(folder, world, progress)
        key = object()
        with self._cond:
            self._live[world] = key
            self._pending.pop(world, None)
            self._written[world] = dict(progress.captures)
        progress.on_change = lambda: self._submit(world, key, Snapshot.of(progress))
        return progress

    def remove(self, world: str) -> bool:
        """Forget ``world``'s progress and remove its files (the student was removed); whether there
        were any. Its Progress, if still in use, saves nothing more. Blocking."""
        folder = self.world_folder(world)
        with self._cond:
            self._live.pop(world, None)
            self._pending.pop(world, None)
            self._written.pop(world, None)
        with self._io:
            try:
                return remove_folder(folder)
            except FileNotFoundError:  # removed meanwhile (a worker sharing this folder did)
                pass
            except OSError as exc:  # the student is removed all the same; say what was left
                log.warning("progress of world %s not removed from %s: %s", world, folder, exc)
                return False
            return True

    # -- a copy kept for another place (handover.py) ---------------------------------------------
    def put(self, world: str, snapshot: Snapshot) -> None:
        """Write ``snapshot`` as ``world``'s progress now: a copy of a world that runs elsewhere (a
        class server's), or one handed over before the world starts here (a worker's). A Progress
        of this world opened before saves nothing more. Blocking."""
        folder = self.world_folder(world)
        with self._cond:
            self._live.pop(world, None)
            self._pending.pop(world, None)
        with self._io:
            folder.mkdir(parents=True, exist_ok=True, mode=0o700)
            self._written[world] = {}
            self._write(world, snapshot)
            for stale in set(capture_names(folder)) - set(snapshot.captures):
                (folder / f"{stale}.png").unlink(missing_ok=True)

    def snapshot(self, world: str, checkpoints: tuple[Checkpoint, ...]) -> Snapshot | None:
        """``world``'s progress as its files keep it (None: none kept), to hand over. Blocking."""
        progress = Progress(checkpoints)
        with self._io:
            self._read(self.world_folder(world), world, progress)
        return Snapshot.of(progress) if progress.version else None

    # -- whose it is (a class server's) -----------------------------------------------------------
    def owner(self, world: str) -> Owner | None:
        """The student ``world``'s files belong to (None: nobody recorded); OwnerFileError for a
        record that cannot be read. Blocking."""
        with self._io:
            return read_owner(self.world_folder(world))

    def has_progress(self, world: str) -> bool:
        """Whether ``world`` has a progress file. Blocking."""
        return (self.world_folder(world) / PROGRESS_FILE).is_file()

    def claim(self, world: str, owner: Owner) -> None:
        """Record ``owner`` as whose ``world``'s files are, from now on, at once: what the world
        keeps from then on (its progress, or its workspace's files, which live elsewhere) is
        theirs even if the server stops before anything else is written. Blocking."""
        folder = self.world_folder(world)
        with self._io:
            folder.mkdir(parents=True, exist_ok=True, mode=0o700)
            write_atomic(folder / OWNER_FILE, owner.encode())

    def release(self, world: str, stamp: str) -> Path | None:
        """Set ``world``'s owner record aside (renamed ``student.json.released-<stamp>``, never
        removed): the next join under its name takes its progress. Where it went; None when there
        was none. Blocking."""
        path = self.world_folder(world) / OWNER_FILE
        with self._io:
            if not path.exists():
                return None
            aside = path.with_name(f"{OWNER_FILE}.released-{stamp}")
            n = 1
            while aside.exists():  # released twice in one second: keep both
                n += 1
                aside = path.with_name(f"{OWNER_FILE}.released-{stamp}-{n}")
            path.rename(aside)
            return aside

    def flush(self, timeout_s: float = CLOSE_WAIT_S) -> bool:
        """Wait until every queued change is written; whether that happened within ``timeout_s``."""
        with self._cond:
            return self._cond.wait_for(lambda: not self._pending and not self._busy, timeout_s)

    def close(self) -> None:
        """Write what is queued, then end the writer's thread."""
        self.flush()
        with self._cond:
            self._closing = True
            self._cond.notify_all()
        if self._thread is not None:
            self._thread.join(CLOSE_WAIT_S)
            self._thread = None
        with self._cond:
            self._closing = False

    # -- reading --------------------------------------------------------------------------------
    def _read(self, folder: Path, world: str, progress: Progress) -> None:
        path = folder / PROGRESS_FILE
        try:
            raw = path.read_bytes()
        except FileNotFoundError:
            return
        except OSError as exc:
            log.warning("progress of world %s: cannot read %s (%s): it starts with none", world, path, exc)
            return
        try:
            taken = decode(raw, progress)
        except SavedProgressError as exc:
            log.warning(
                "progress of world %s: %s is not a progress file (%s): it starts with none, "
                "and the file is kept as %s.corrupt",
                world,
                path,
                exc,
                path.name,
            )
            with contextlib.suppress(OSError):  # set aside for a human to look at, if it can be
                path.replace(path.with_name(path.name + ".corrupt"))
            return
        for checkpoint in progress.checkpoints:
            png = read_capture(folder, checkpoint.name)
            if png is not None:
                progress.captures[checkpoint.name] = png
                taken += 1
        progress.version = taken
        log.info("progress of world %s: %d saved item(s) read from %s", world, taken, folder)

    # -- writing (the writer's thread) ----------------------------------------------------------
    def _submit(self, world: str, key: object, snapshot: Snapshot) -> None:
        with self._cond:
            if self._live.get(world) is not key:
                return  # removed, or opened again since: this Progress is no longer the world's
            self._pending[world] = (key, snapshot)
            if self._thread is None:
                self._thread = threading.Thread(target=self._run, name="progress store", daemon=True)
                self._thread.start()
            self._cond.notify_all()

    def _run(self) -> None:
        while True:
            with self._cond:
                self._cond.wait_for(lambda: self._pending or self._closing)
                if not self._pending:
                    return
                world, (key, snapshot) = self._pending.popitem()
                self._busy = True
            try:
                with self._io:
                    if self._live.get(world) is key:
                        self._write(world, snapshot)
            except OSError as exc:
                log.warning("progress of world %s not saved: %s", world, exc)
            except Exception:  # evidence that is not JSON, say: that world's file, not the writer, fails
                log.exception("progress of world %s not saved", world)
            finally:
                with self._cond:
                    self._busy = False
                    self._cond.notify_all()

    def _write(self, world: str, snapshot: Snapshot) -> None:
        folder = self.world_folder(world)
        folder.mkdir(parents=True, exist_ok=True, mode=0o700)
        written = self._written.setdefault(world, {})
        for name, png in snapshot.captures.items():
            if written.get(name) is not png and _NAME.fullmatch(name):
                write_atomic(folder / f"{name}.png", png)
                written[name] = png
        write_atomic(folder / PROGRESS_FILE, encode(snapshot))


def capture_names(folder: Path) -> list[str]:
    """The checkpoints whose captures ``folder`` holds a file of."""
    try:
        return [p.stem for p in folder.glob("*.png") if _NAME.fullmatch(p.stem)]
    except OSError:
        return []


def read_capture(folder: Path, name: str) -> bytes | None:
    """Checkpoint ``name``'s capture in world folder ``folder``, if it holds a good one."""
    if not _NAME.fullmatch(name):
        return None
    path = folder / f"{name}.png"
    try:
        if path.stat().st_size > MAX_CAPTURE_BYTES:
            log.warning("capture %s is larger than %d bytes: left out", path, MAX_CAPTURE_BYTES)
            return None
        png = path.read_bytes()
    except OSError:
        return None
    if not capture_ok(png):
        log.warning("capture %s is not a PNG of at most %d bytes: left out", path, MAX_CAPTURE_BYTES)
        return None
    return png


def write_atomic(path: Path, data: bytes) -> None:
    fd, temp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.")
    try:
        with os.fdopen(fd, "wb") as out:
            out.write(data)
            out.flush()
            os.fsync(out.fileno())
        os.replace(temp, path)
    except BaseException:
        Path(temp).unlink(missing_ok=True)
        raise
