"""A folder of a workspace removed with everything in it, by a loop rather than recursion: a node
can nest folders far past Python's recursion limit (shutil.rmtree recurses in Python 3.11). Each
folder is opened inside the one above it without following a link (``handles.py``), and a link in
it is unlinked, never followed. At most MAX_OPEN folders are open at once: a folder deeper than
that is first moved up into the top one, under a hidden name, and removed from there.
"""

from __future__ import annotations

import errno
import os
import secrets
from dataclasses import dataclass

from server.services.workspace.errors import TakenError
from server.services.workspace.handles import FOLDER, NOT_A_FOLDER, NotAFolderError, folder_in

MAX_OPEN = 32  # folders open at once; a deeper one is moved up to the top first
RESCANS = 3  # times a folder that filled while it was emptied is listed again


@dataclass
class _Opened:
    """A folder being emptied: its fd, its name in the folder above, the folders in it still to empty."""

    fd: int
    name: str
    folders: list[str] | None = None  # None: not listed yet
    listings: int = 0


def remove_folder(parent: int, name: str, relative: str) -> int:
    """Remove the folder ``name`` of the open folder ``parent`` with everything in it; how many
    files (and links) went. Folders are opened as the rest are (a link in their place is
    unlinked), at most MAX_OPEN at once: one deeper than that is first moved up into the top one."""
    try:
        top = folder_in(parent, name, relative, 0, make=False)
    except NotAFolderError:
        raise TakenError(f"{relative} is no folder any more") from None
    if top is None:
        return 0
    removed = 0
    stack = [_Opened(top, name)]
    try:
        while stack:
            current = stack[-1]
            if current.folders is None:
                current.folders, count = _empty_of_files(current.fd)
                removed, current.listings = removed + count, current.listings + 1
            if current.folders:
                below = current.folders.pop()
                if len(stack) >= MAX_OPEN:
                    moved = f".removing.{secrets.token_hex(8)}"
                    os.rename(below, moved, src_dir_fd=current.fd, dst_dir_fd=stack[0].fd)
                    assert stack[0].folders is not None
                    stack[0].folders.append(moved)
                    continue
                try:
                    stack.append(_Opened(os.open(below, FOLDER, dir_fd=current.fd), below))
                except FileNotFoundError:
                    pass
                except OSError as exc:
                    if exc.errno not in NOT_A_FOLDER:
                        raise
                    os.unlink(below, dir_fd=current.fd)  # a link (or file) since it was listed
                    removed += 1
                continue
            try:
                os.rmdir(current.name, dir_fd=stack[-2].fd if len(stack) > 1 else parent)
            except OSError as exc:
                if exc.errno != errno.ENOTEMPTY or current.listings > RESCANS:
                    raise TakenError(f"{relative} kept filling while it was removed: {exc}") from None
                current.folders = None  # something came in meanwhile: list it again
                continue
            os.close(stack.pop().fd)
    finally:
        for opened in stack:
            os.close(opened.fd)
    return removed


def _empty_of_files(folder: int) -> tuple[list[str], int]:
    """Unlink everything in the open folder but its folders (a link is unlinked, never followed);
    the folders' names and how many files and links went."""
    folders: list[str] = []
    count = 0
    with os.scandir(folder) as found:
        items = list(found)
    for item in items:
        if item.is_dir(follow_symlinks=False):
            folders.append(item.name)
            continue
        counted = item.is_symlink() or item.is_file(follow_symlinks=False)
        try:
            os.unlink(item.name, dir_fd=folder)
        except FileNotFoundError:
            continue
        except IsADirectoryError:  # a folder since it was listed
            folders.append(item.name)
            continue
        count += counted
    return folders, count
