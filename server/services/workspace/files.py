"""A workspace's files, read and written through the API: confined to its folder, within its
limits, and with versions (etags) so that a save from a stale copy is refused, not lost.

Every path is opened one folder at a time from the workspace's own, never through a symbolic link
(``handles.py``): a process writing in the workspace may swap anything for a link at any moment. A
save writes a new file beside the old one under a random name and renames it over (a reader never
sees half a file, and the etag changes with the new inode). Every check runs before anything is
written. Calls come from worker threads, so writes hold one lock.
"""

from __future__ import annotations

import os
import stat
import threading
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Literal

from server.host.settings import WorkspaceLimits
from server.services.workspace.errors import (
    ChangedError,
    FileMissingError,
    NotTextError,
    TakenError,
    TooLargeError,
)
from server.services.workspace.handles import (
    NotAFolderError,
    descend,
    file_at,
    lstat_in,
    make_root,
    open_root,
    read_at_most,
    through_link,
    write_file,
)
from server.services.workspace.paths import parts_of
from server.services.workspace.removal import remove_folder
from server.services.workspace.tree import Tree, etag_of, walk

# What a folder missing on the way means: "read": no such path; "check": none yet (a file where
# one goes is TakenError); "make": made.
Way = Literal["read", "check", "make"]


@dataclass(frozen=True)
class TextFile:
    path: str
    text: str
    etag: str


@dataclass(frozen=True)
class Saved:
    path: str
    etag: str
    size: int
    created: bool


def encode_text(path: str, text: str) -> bytes:
    """The file's bytes; NotTextError for text a source file cannot hold (a NUL: binary)."""
    if "\x00" in text:
        raise NotTextError(f"{path}: the text holds a NUL character; only text files go in a workspace")
    try:
        return text.encode("utf-8")
    except UnicodeEncodeError as exc:  # a lone surrogate from JSON's \\ud800
        raise NotTextError(f"{path}: the text is not valid Unicode ({exc.reason})") from None


def decode_text(path: str, data: bytes) -> str:
    """The bytes as text; NotTextError when they are not UTF-8 text."""
    if b"\x00" in data:
        raise NotTextError(f"{path} is not a text file (it holds NUL bytes)")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        raise NotTextError(f"{path} is not UTF-8 text") from None


def write_atomic(path: Path, data: bytes) -> None:
    """``data`` in ``path``, replacing what was there in one step (a new inode, so a new etag), its
    folders made; for a folder of the caller's own (``ros2lab pkg create``): the path is followed."""
    path.parent.mkdir(parents=True, exist_ok=True)
    folder = os.open(path.parent, os.O_RDONLY | os.O_DIRECTORY | os.O_CLOEXEC)
    try:
        write_file(folder, path.name, data)
    finally:
        os.close(folder)


class WorkspaceFiles:
    """The files of the workspace at ``root`` (which may not exist yet: the first save makes it)."""

    def __init__(self, root: Path, limits: WorkspaceLimits) -> None:
        self.root = root
        self.limits = limits
        self.lock = threading.Lock()

    def tree(self) -> Tree:
        return walk(self.root, self.max_entries, self.limits.max_depth)

    @property
    def max_entries(self) -> int:
        return 4 * self.limits.max_files  # files and their folders; past it the walk stops

    def parts(self, relative: str) -> tuple[str, ...]:
        return parts_of(relative, self.limits.max_depth)

    @contextmanager
    def opened(self, relative: str) -> Iterator[tuple[int, os.stat_result] | None]:
        """The file ``relative``, open for reading with its ``fstat`` (None: no such file)."""
        with file_at(self.root, self.parts(relative), relative) as found:
            yield found

    def read(self, relative: str) -> TextFile:
        limit = self.limits.max_file_bytes
        with self.opened(relative) as found:
            if found is None:
                raise FileMissingError(f"no file {relative!r} in the workspace")
            fd, status = found
            if status.st_size > limit:
                raise TooLargeError(f"{relative} is larger than {limit} bytes")
            data = read_at_most(fd, limit)
        if len(data) > limit:  # it grew since
            raise TooLargeError(f"{relative} is larger than {limit} bytes")
        return TextFile(relative, decode_text(relative, data), etag_of(status))

    def etag(self, relative: str) -> str | None:
        with self.opened(relative) as found:
            return etag_of(found[1]) if found is not None else None

    def write(
        self, relative: str, text: str, *, if_match: str | None = None, create_only: bool = False
    ) -> Saved:
        """Save ``text``: over the version ``if_match`` names, or only if there is no file yet."""
        data = encode_text(relative, text)
        with self.lock:
            found = self.probe(relative)
            if found is not None and stat.S_ISDIR(found.st_mode):
                raise TakenError(f"{relative!r} is a folder")
            current = etag_of(found) if found is not None and stat.S_ISREG(found.st_mode) else None
            if create_only and current is not None:
                raise ChangedError(f"{relative} exists already (If-None-Match: *)", current)
            if if_match is not None and if_match != current:
                raise ChangedError(
                    f"{relative} changed since it was read: its version is not {if_match!r}", current
                )
            self.check_room({relative: len(data)})
            written = self.put(relative, data)
            return Saved(relative, etag_of(written), len(data), created=current is None)

    def check_room(self, adding: dict[str, int]) -> None:
        """TooLargeError unless the workspace can take these files (path → size), replacing any
        file of the same path."""
        for relative, size in adding.items():
            if size > self.limits.max_file_bytes:
                raise TooLargeError(
                    f"{relative}: {size} bytes, over the limit of {self.limits.max_file_bytes} per file"
                )
        sizes = {e.path: e.size for e in self.tree().files} | adding
        if len(sizes) > self.limits.max_files:
            raise TooLargeError(
                f"the workspace would hold {len(sizes)} files, over its limit of {self.limits.max_files}"
            )
        total = sum(sizes.values())
        if total > self.limits.max_workspace_bytes:
            raise TooLargeError(
                f"the workspace would hold {total} bytes, over its limit of {self.limits.max_workspace_bytes}"
            )

    # -- for callers that hold the lock (this class, a zip's upload, a new package) --

    def probe(self, relative: str) -> os.stat_result | None:
        """What is at ``relative`` now, itself (None: nothing yet), checked as a write checks its
        target: a link on the way or there is BadPathError, a file where a folder goes TakenError."""
        parts = self.parts(relative)
        with self.folder(parts[:-1], relative, "check") as folder:
            found = lstat_in(folder, parts[-1]) if folder is not None else None
        if found is not None and stat.S_ISLNK(found.st_mode):
            raise through_link(relative)
        return found

    def put(self, relative: str, data: bytes) -> os.stat_result:
        """Write ``data`` as ``relative`` (its folders made), replacing a file in one step; its stat."""
        parts = self.parts(relative)
        with self.folder(parts[:-1], relative, "make") as folder:
            assert folder is not None
            return write_file(folder, parts[-1], data)

    def make_folder(self, relative: str) -> None:
        with self.folder(self.parts(relative), relative, "make"):
            pass

    @contextmanager
    def folder(self, parts: Sequence[str], relative: str, way: Way) -> Iterator[int | None]:
        """The folder ``parts`` (none: the workspace's own) open for the ``with`` block; None when
        it is not there (see ``Way``)."""
        top = make_root(self.root) if way == "make" else open_root(self.root)
        if top is None:
            yield None
            return
        try:
            folder, depth = descend(top, parts, relative, make=way == "make")
        except NotAFolderError as exc:
            if way == "read":
                folder, depth = -1, 0
            else:
                taken = "/".join(parts[: exc.depth + 1])
                raise TakenError(f"{taken} is a file: it cannot hold {relative}") from None
        finally:
            os.close(top)
        try:
            yield folder if folder >= 0 and depth == len(parts) else None
        finally:
            if folder >= 0:
                os.close(folder)

    def delete(self, relative: str, *, if_match: str | None = None) -> int:
        """Remove a file or a folder with all in it; how many files went."""
        parts = self.parts(relative)
        with self.lock, self.folder(parts[:-1], relative, "read") as folder:
            found = lstat_in(folder, parts[-1]) if folder is not None else None
            if found is not None and stat.S_ISLNK(found.st_mode):
                raise through_link(relative)
            if found is not None and stat.S_ISREG(found.st_mode):
                current = etag_of(found)
                if if_match is not None and if_match != current:
                    raise ChangedError(f"{relative} changed since it was read", current)
                os.unlink(parts[-1], dir_fd=folder)
                return 1
            if found is None or not stat.S_ISDIR(found.st_mode):
                raise FileMissingError(f"no file or folder {relative!r} in the workspace")
            if if_match is not None:
                raise ChangedError(f"{relative} is a folder: If-Match names a file's version", None)
            assert folder is not None
            return remove_folder(folder, parts[-1], relative)

    def rename(self, source: str, target: str) -> str:
        """Move a file or folder to a path that is free (TakenError otherwise)."""
        old, new = self.parts(source), self.parts(target)
        if new[: len(old)] == old:
            raise TakenError(f"{target!r} is inside {source!r}: a folder cannot move into itself")
        with self.lock, self.folder(old[:-1], source, "read") as old_folder:
            found = lstat_in(old_folder, old[-1]) if old_folder is not None else None
            if found is not None and stat.S_ISLNK(found.st_mode):
                raise through_link(source)
            if found is None or not (stat.S_ISREG(found.st_mode) or stat.S_ISDIR(found.st_mode)):
                raise FileMissingError(f"no file or folder {source!r} in the workspace")
            if self.probe(target) is not None:
                raise TakenError(f"{target!r} exists already")
            assert old_folder is not None
            with self.folder(new[:-1], target, "make") as new_folder:
                os.rename(old[-1], new[-1], src_dir_fd=old_folder, dst_dir_fd=new_folder)
        return target
