"""A workspace's tree: its files and folders with sizes and versions, read from the disk's
metadata alone (a bounded walk of ``stat`` calls, no file is read), so the page can ask often.

A file's ``etag`` changes whenever the file does: it hashes the inode, size and change times, and
every save here replaces the file with a new one (a new inode). The tree's ``version`` hashes
every entry's path and etag, so an edit, a new file or a removal made by anyone (a terminal user's
editor too) gives a new version. Symbolic links, hidden names and names the workspace would not
take are neither listed nor followed.
"""

from __future__ import annotations

import hashlib
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Literal

from .paths import NAME

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

    @property
    def files(self) -> list[Entry]:
        return [e for e in self.entries if e.kind == "file"]

    @property
    def total_bytes(self) -> int:
        return sum(e.size for e in self.entries)


def etag_of(stat: os.stat_result) -> str:
    key = f"{stat.st_ino}:{stat.st_size}:{stat.st_mtime_ns}:{stat.st_ctime_ns}"
    return hashlib.sha1(key.encode(), usedforsecurity=False).hexdigest()[:20]


def walk(root: Path, max_entries: int) -> Tree:
    """Every entry under ``root``, sorted by path; at most ``max_entries`` of them."""
    entries: list[Entry] = []
    if root.is_dir() and not root.is_symlink():
        _walk(root, "", entries, max_entries)
    entries.sort(key=lambda e: e.path)
    if not entries:
        return Tree(EMPTY_VERSION, entries)
    digest = hashlib.sha1(usedforsecurity=False)
    for e in entries:
        digest.update(f"{e.path}\0{e.kind}\0{e.etag}\n".encode())
    return Tree(digest.hexdigest()[:20], entries)


def _walk(folder: Path, prefix: str, entries: list[Entry], max_entries: int) -> None:
    try:
        with os.scandir(folder) as found:
            items = sorted(found, key=lambda d: d.name)
    except OSError:
        return
    for item in items:
        if len(entries) >= max_entries:
            return
        if not NAME.match(item.name) or item.is_symlink():
            continue
        path = f"{prefix}{item.name}"
        try:
            stat = item.stat(follow_symlinks=False)
        except OSError:
            continue
        if item.is_dir(follow_symlinks=False):
            entries.append(Entry(path, "dir", 0, None))
            _walk(Path(item.path), f"{path}/", entries, max_entries)
        elif item.is_file(follow_symlinks=False):
            entries.append(Entry(path, "file", stat.st_size, etag_of(stat)))
