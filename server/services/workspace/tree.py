"""A workspace's tree: its files and folders with sizes and versions, read from the disk's
metadata alone (a bounded walk of ``stat`` calls, no file is read), so the page can ask often.

A file's ``etag`` changes whenever the file does: it hashes the inode, size and change times, and
every save here replaces the file with a new one (a new inode). The tree's ``version`` hashes
every entry's path and etag, so an edit, a new file or a removal made by anyone (a terminal user's
editor too) gives a new version. Symbolic links, hidden names and names the workspace would not
take are neither listed nor followed: each folder is opened inside the one above it, never through
a link (``handles.py``).

The walk is a loop over a stack of open folders, not a recursion, and goes at most ``max_depth``
names down (a path the API takes); what lies just past that is counted, with one example, and not
listed, nor anything it holds (a node can nest folders far past Python's recursion limit).
"""

from __future__ import annotations

import hashlib
import os
import stat
from dataclasses import dataclass
from pathlib import Path
from typing import Literal

from server.services.workspace.errors import WorkspaceFileError
from server.services.workspace.handles import FOLDER, open_root
from server.services.workspace.paths import NAME

Kind = Literal["file", "dir"]
EMPTY_VERSION = "empty"


@dataclass(frozen=True)
class Entry:
    path: str  # POSIX, relative to the workspace
    kind: Kind
    size: int  # bytes (0 for a folder)
    etag: str | None  # None for a folder


@dataclass(frozen=True)
class Tree:
    version: str
    entries: list[Entry]
    too_deep: int = 0  # entries just past the depth limit, not listed (nor what they hold)
    too_deep_example: str | None = None  # the path of one of them

    @property
    def files(self) -> list[Entry]:
        return [e for e in self.entries if e.kind == "file"]

    @property
    def total_bytes(self) -> int:
        return sum(e.size for e in self.entries)


def etag_of(stat: os.stat_result) -> str:
    key = f"{stat.st_ino}:{stat.st_size}:{stat.st_mtime_ns}:{stat.st_ctime_ns}"
    return hashlib.sha1(key.encode(), usedforsecurity=False).hexdigest()[:20]


def walk(root: Path, max_entries: int, max_depth: int) -> Tree:
    """Every entry under ``root`` down to ``max_depth`` names, sorted by path; at most
    ``max_entries`` of them."""
    walk = _Walk(max_entries, max_depth)
    try:
        top = open_root(root)
    except WorkspaceFileError:  # the folder is a link or a file: nothing to list
        top = None
    if top is not None:
        walk.run(top)
    entries = sorted(walk.entries, key=lambda e: e.path)
    if not entries:
        return Tree(EMPTY_VERSION, entries)
    digest = hashlib.sha1(usedforsecurity=False)
    for e in entries:
        digest.update(f"{e.path}\0{e.kind}\0{e.etag}\n".encode())
    if walk.too_deep:
        digest.update(f"{walk.too_deep}\0{walk.example}".encode())
    return Tree(digest.hexdigest()[:20], entries, walk.too_deep, walk.example)


class _Walk:
    def __init__(self, max_entries: int, max_depth: int) -> None:
        self.max_entries, self.max_depth = max_entries, max_depth
        self.entries: list[Entry] = []
        self.too_deep = 0
        self.example: str | None = None

    def run(self, top: int) -> None:
        """Depth first from the open folder ``top`` (closed at the end, with every folder below)."""
        stack = [(top, "", iter(_listing(top)))]
        try:
            while stack and len(self.entries) < self.max_entries:
                folder, prefix, items = stack[-1]
                item = next(items, None)
                if item is None:
                    os.close(stack.pop()[0])
                    continue
                below = self.visit(folder, item, prefix)
                if below is not None:
                    path = f"{prefix}{item.name}"
                    if len(stack) < self.max_depth:
                        stack.append((below, f"{path}/", iter(_listing(below))))
                    else:
                        self.count_below(below, path)
        finally:
            for folder, _, _ in stack:
                os.close(folder)

    def visit(self, folder: int, item: os.DirEntry[str], prefix: str) -> int | None:
        """List ``item``; a folder is opened (inside ``folder``) and its fd returned."""
        if not NAME.match(item.name) or item.is_symlink():
            return None
        path = f"{prefix}{item.name}"
        try:
            found = item.stat(follow_symlinks=False)
        except OSError:
            return None
        if stat.S_ISREG(found.st_mode):
            self.entries.append(Entry(path, "file", found.st_size, etag_of(found)))
        elif stat.S_ISDIR(found.st_mode):
            self.entries.append(Entry(path, "dir", 0, None))
            try:
                return os.open(item.name, FOLDER, dir_fd=folder)
            except OSError:  # gone, or a link since it was listed
                return None
        return None

    def count_below(self, folder: int, path: str) -> None:
        """Count what ``folder`` (at the depth limit, open) holds, without listing it; close it."""
        try:
            names = [d.name for d in _listing(folder) if NAME.match(d.name) and not d.is_symlink()]
        finally:
            os.close(folder)
        if names and self.example is None:
            self.example = f"{path}/{names[0]}"
        self.too_deep += len(names)


def _listing(folder: int) -> list[os.DirEntry[str]]:
    try:
        with os.scandir(folder) as found:
            return sorted(found, key=lambda d: d.name)
    except OSError:
        return []
