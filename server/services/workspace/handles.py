"""A workspace's folders and files opened one name at a time, never through a symbolic link.

A path checked on the disk and then opened by its name can change in between: a process that
writes in the workspace (a student's node) can swap a file or a folder for a link to anything the
server may read or write, and an open by name follows it. So every read and write of the API
starts from the workspace's folder opened with O_NOFOLLOW and opens each folder below it relative
to the one above (``dir_fd``), with O_NOFOLLOW again, and the file last: a link anywhere fails the
open itself (BadPathError), and what is read, written or removed is what was opened. A file's
size and version come from ``fstat`` of the open file, and its bytes from that same file.

A new file is written under a random hidden name made with O_EXCL (never through a link a node
left at a name it could guess) and renamed over the old one in the same folder. A folder with all
in it is removed the same way (``removal.py``).
"""

from __future__ import annotations

import errno
import os
import secrets
import stat
from collections.abc import Iterator, Sequence
from contextlib import contextmanager, suppress
from pathlib import Path

from server.services.workspace.errors import BadPathError, NoWorkspaceError, TakenError

FOLDER = os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | os.O_CLOEXEC
# O_NONBLOCK: a FIFO left where a file was expected opens at once (and is then passed over as no
# regular file) instead of waiting for a writer that never comes.
READ = os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_CLOEXEC
FILE_MODE = 0o644  # the workspace's files and folders are readable by all: a sandboxed node runs
FOLDER_MODE = 0o755  # as its world's uid, with the workspace bound read-only
CREATE = os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW | os.O_CLOEXEC
NOT_A_FOLDER = (errno.ENOTDIR, errno.ELOOP)  # O_DIRECTORY|O_NOFOLLOW on a link: ENOTDIR on Linux
CHUNK = 64 * 1024
ATTEMPTS = 8  # tries for a fresh temporary name, or a folder made while another removes it


class NotAFolderError(Exception):
    """Something other than a folder (a file) where a folder of a path goes: ``depth`` names of
    the path lead to it."""

    def __init__(self, depth: int) -> None:
        super().__init__(f"not a folder at depth {depth}")
        self.depth = depth


def through_link(relative: str) -> BadPathError:
    return BadPathError(f"{relative!r} goes through a symbolic link, which could lead out of the workspace")


def lstat_in(folder: int, name: str) -> os.stat_result | None:
    """What ``name`` is in the open folder, itself (a link is a link); None: nothing."""
    try:
        return os.stat(name, dir_fd=folder, follow_symlinks=False)
    except FileNotFoundError:
        return None


def open_root(root: Path) -> int | None:
    """The workspace's folder, open (None: there is none yet); the folder itself is no link."""
    try:
        return os.open(root, FOLDER)
    except FileNotFoundError:
        return None
    except OSError as exc:
        if exc.errno not in NOT_A_FOLDER:
            raise
        if root.is_symlink():
            raise BadPathError(f"the workspace folder {root.name!r} is a symbolic link") from None
        raise NoWorkspaceError(f"the workspace {root.name!r} is not a folder") from None


def make_root(root: Path) -> int:
    """The workspace's folder, open, made first if there is none (with the server's folders above)."""
    with suppress(FileExistsError):  # a file or a link there: open_root says which
        root.mkdir(parents=True, exist_ok=True)
    found = open_root(root)
    if found is None:
        raise NoWorkspaceError(f"the workspace {root.name!r} went while it was made")
    return found


def descend(top: int, names: Sequence[str], relative: str, *, make: bool = False) -> tuple[int, int]:
    """Open the folders ``names``, each inside the one before, from the open folder ``top``: a new
    fd of the deepest one there and how many of ``names`` that took (fewer than all: the next one
    is missing). With ``make`` a missing one is made. A link on the way is BadPathError, anything
    else that is not a folder NotAFolderError; ``top`` stays open."""
    folder = os.dup(top)
    try:
        for depth, name in enumerate(names):
            below = folder_in(folder, name, relative, depth, make)
            if below is None:
                return folder, depth
            os.close(folder)
            folder = below
    except BaseException:
        os.close(folder)
        raise
    return folder, len(names)


def folder_in(folder: int, name: str, relative: str, depth: int, make: bool) -> int | None:
    """The folder ``name`` in the open folder, opened (None: not there, and not ``make``); the
    errors of ``descend``, ``depth`` names down ``relative``."""
    for _ in range(ATTEMPTS):
        try:
            return os.open(name, FOLDER, dir_fd=folder)
        except FileNotFoundError:
            if not make:
                return None
        except OSError as exc:
            if exc.errno not in NOT_A_FOLDER:
                raise
            found = lstat_in(folder, name)
            if found is not None and stat.S_ISLNK(found.st_mode):
                raise through_link(relative) from None
            raise NotAFolderError(depth) from None
        with suppress(FileExistsError):  # made meanwhile: opened (or refused) at the next turn
            os.mkdir(name, FOLDER_MODE, dir_fd=folder)
            _open_to_all(folder, name)
    raise TakenError(f"{relative}: a folder on its way kept going while it was made")


def _open_to_all(folder: int, name: str) -> None:
    """The folder just made readable by all, whatever the server's umask (a sandboxed node lists
    it as another uid). Swapped meanwhile: the next turn's open refuses what is there."""
    with suppress(OSError):
        made = os.open(name, FOLDER, dir_fd=folder)
        try:
            os.fchmod(made, FOLDER_MODE)
        finally:
            os.close(made)


def open_file(folder: int, name: str, relative: str) -> tuple[int, os.stat_result] | None:
    """The regular file ``name`` of the open folder, open for reading, with its ``fstat`` (None:
    no regular file there: nothing, a folder, a FIFO). A link is BadPathError."""
    try:
        fd = os.open(name, READ, dir_fd=folder)
    except FileNotFoundError:
        return None
    except OSError as exc:
        if exc.errno == errno.ELOOP:
            raise through_link(relative) from None
        if exc.errno == errno.ENXIO:  # a socket
            return None
        raise
    try:
        found = os.fstat(fd)
    except BaseException:
        os.close(fd)
        raise
    if not stat.S_ISREG(found.st_mode):
        os.close(fd)
        return None
    return fd, found


@contextmanager
def file_at(root: Path, parts: Sequence[str], relative: str) -> Iterator[tuple[int, os.stat_result] | None]:
    """The regular file at ``parts`` in the workspace at ``root``, open for reading with its
    ``fstat``, for the ``with`` block (None: no such file). A link on the way is BadPathError."""
    opened = None
    top = open_root(root)
    if top is not None:
        try:
            folder, depth = descend(top, parts[:-1], relative)
        except NotAFolderError:
            folder, depth = -1, 0
        finally:
            os.close(top)
        if folder >= 0:
            try:
                if depth == len(parts) - 1:
                    opened = open_file(folder, parts[-1], relative)
            finally:
                os.close(folder)
    try:
        yield opened
    finally:
        if opened is not None:
            os.close(opened[0])


def read_at_most(fd: int, limit: int) -> bytes:
    """The open file's bytes from where it stands, at most ``limit`` + 1 of them (one more than the
    limit: the file is larger than it)."""
    chunks: list[bytes] = []
    read = 0
    while read <= limit:
        chunk = os.read(fd, min(CHUNK, limit + 1 - read))
        if not chunk:
            break
        chunks.append(chunk)
        read += len(chunk)
    return b"".join(chunks)


def write_file(folder: int, name: str, data: bytes) -> os.stat_result:
    """``data`` as the file ``name`` of the open folder, replacing what was there in one step (a
    new inode, so a new etag); the new file's ``fstat``."""
    temporary, fd = _temporary(folder, name)
    replaced = False
    try:
        view = memoryview(data)
        while view:
            view = view[os.write(fd, view) :]
        os.replace(temporary, name, src_dir_fd=folder, dst_dir_fd=folder)
        replaced = True
        return os.fstat(fd)
    finally:
        os.close(fd)
        if not replaced:
            with suppress(FileNotFoundError):
                os.unlink(temporary, dir_fd=folder)


def _temporary(folder: int, name: str) -> tuple[str, int]:
    """A new empty file beside ``name`` under a random hidden name (the tree lists no hidden name)."""
    for _ in range(ATTEMPTS):
        temporary = f".{name[:64]}.{secrets.token_hex(8)}.saving"
        try:
            fd = os.open(temporary, CREATE, FILE_MODE, dir_fd=folder)
        except FileExistsError:
            continue
        os.fchmod(fd, FILE_MODE)  # whatever the server's umask: a sandboxed node reads it as another uid
        return temporary, fd
    raise FileExistsError(errno.EEXIST, f"no free temporary name beside {name}")
