"""A workspace's files, read and written through the API: confined to its folder, within its
limits, and with versions (etags) so that a save from a stale copy is refused, not lost.

A save writes a new file beside the old one and renames it over (a reader never sees half a file,
and the etag changes with the new inode). Every check runs before anything is written. Calls come
from the event loop (small files) and from worker threads (a zip), so writes hold one lock.
"""

from __future__ import annotations

import os
import shutil
import threading
from dataclasses import dataclass
from pathlib import Path

from server.settings import WorkspaceLimits

from .errors import ChangedError, FileMissingError, NotTextError, TakenError, TooLargeError
from .paths import confine, parts_of
from .tree import Tree, etag_of, walk


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


def check_parents(root: Path, path: Path, relative: str) -> None:
    """TakenError when a folder on the way to ``path`` is a file (it could not hold it)."""
    for parent in reversed(path.relative_to(root).parents[:-1]):
        if (root / parent).exists() and not (root / parent).is_dir():
            raise TakenError(f"{parent.as_posix()} is a file: it cannot hold {relative}")


def write_atomic(path: Path, data: bytes) -> None:
    """``data`` in ``path``, replacing what was there in one step (a new inode, so a new etag)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    temporary = path.with_name(f".{path.name}.saving")
    temporary.write_bytes(data)
    os.replace(temporary, path)


class WorkspaceFiles:
    """The files of the workspace at ``root`` (which may not exist yet: the first save makes it)."""

    def __init__(self, root: Path, limits: WorkspaceLimits) -> None:
        self.root = root
        self.limits = limits
        self.lock = threading.Lock()

    def tree(self) -> Tree:
        return walk(self.root, self.max_entries)

    @property
    def max_entries(self) -> int:
        return 4 * self.limits.max_files  # files and their folders; past it the walk stops

    def read(self, relative: str) -> TextFile:
        path = confine(self.root, relative)
        if not path.is_file():
            raise FileMissingError(f"no file {relative!r} in the workspace")
        if path.stat().st_size > self.limits.max_file_bytes:
            raise TooLargeError(f"{relative} is larger than {self.limits.max_file_bytes} bytes")
        stat = path.stat()
        data = path.read_bytes()
        return TextFile(relative, decode_text(relative, data), etag_of(stat))

    def etag(self, relative: str) -> str | None:
        path = confine(self.root, relative)
        return etag_of(path.stat()) if path.is_file() else None

    def write(
        self, relative: str, text: str, *, if_match: str | None = None, create_only: bool = False
    ) -> Saved:
        """Save ``text``: over the version ``if_match`` names, or only if there is no file yet."""
        path = confine(self.root, relative)
        data = encode_text(relative, text)
        with self.lock:
            if path.is_dir():
                raise TakenError(f"{relative!r} is a folder")
            check_parents(self.root, path, relative)
            current = etag_of(path.stat()) if path.is_file() else None
            if create_only and current is not None:
                raise ChangedError(f"{relative} exists already (If-None-Match: *)", current)
            if if_match is not None and if_match != current:
                raise ChangedError(
                    f"{relative} changed since it was read: its version is not {if_match!r}", current
                )
            self.check_room({relative: len(data)})
            write_atomic(path, data)
            return Saved(relative, etag_of(path.stat()), len(data), created=current is None)

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

    def delete(self, relative: str, *, if_match: str | None = None) -> int:
        """Remove a file or a folder with all in it; how many files went."""
        path = confine(self.root, relative)
        with self.lock:
            if path.is_file():
                current = etag_of(path.stat())
                if if_match is not None and if_match != current:
                    raise ChangedError(f"{relative} changed since it was read", current)
                path.unlink()
                return 1
            if not path.is_dir():
                raise FileMissingError(f"no file or folder {relative!r} in the workspace")
            if if_match is not None:
                raise ChangedError(f"{relative} is a folder: If-Match names a file's version", None)
            files = sum(1 for p in path.rglob("*") if p.is_file() or p.is_symlink())
            shutil.rmtree(path)
            return files

    def rename(self, source: str, target: str) -> str:
        """Move a file or folder to a path that is free (TakenError otherwise)."""
        old, new = confine(self.root, source), confine(self.root, target)
        if parts_of(target)[: len(parts_of(source))] == parts_of(source):
            raise TakenError(f"{target!r} is inside {source!r}: a folder cannot move into itself")
        with self.lock:
            if not (old.is_file() or old.is_dir()):
                raise FileMissingError(f"no file or folder {source!r} in the workspace")
            if new.exists() or new.is_symlink():
                raise TakenError(f"{target!r} exists already")
            check_parents(self.root, new, target)
            new.parent.mkdir(parents=True, exist_ok=True)
            os.rename(old, new)
        return target
