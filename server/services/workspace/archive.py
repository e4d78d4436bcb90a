"""A workspace as one zip, out and in.

Out: every file the tree lists, under its path, each read from the file the walk opened (never
through a link, ``handles.py``), into a temporary file rather than memory (a workspace a node
filled may be far larger than the limits of what the API writes); the caller sends it from there.
In: every entry is checked before anything is written, and one bad entry refuses the whole upload:
a name that is not a workspace path (``..``, absolute, a backslash), a symbolic link, an encrypted
entry, a name given twice, more entries than the workspace may hold, an entry or a total over the
limits by its declared size or by what it really inflates to (a zip bomb lies in its header; the
reading stops one byte past the limit), and content that is not UTF-8 text.
"""

from __future__ import annotations

import errno
import io
import os
import stat
import tempfile
import time
import zipfile
import zlib
from collections.abc import Mapping
from contextlib import ExitStack
from typing import IO, Literal

from server.services.workspace.errors import (
    BadArchiveError,
    BadPathError,
    NotTextError,
    TakenError,
    TooLargeError,
)
from server.services.workspace.files import WorkspaceFiles, decode_text
from server.services.workspace.handles import NotAFolderError, descend, lstat_in, open_root, through_link
from server.services.workspace.paths import parts_of
from server.services.workspace.removal import remove_folder

READ_CHUNK = 64 * 1024
# An entry whose first chunk deflates to more than this share of itself is stored as it is:
# deflate spends about 30 s of CPU a GiB on bytes it cannot shrink (random, already compressed).
STORED_ABOVE = 0.9
SMALL = 4096  # bytes below which an entry is always deflated (its sample says little)
EARLIEST = (1980, 1, 1, 0, 0, 0)  # the times a zip can hold
LATEST = (2107, 12, 31, 23, 59, 58)


def packed(sources: Mapping[str, WorkspaceFiles]) -> IO[bytes]:
    """The files of every workspace in one zip, each under its folder (the key: '' or 'ada/') and
    its path: a temporary file, at its start, that the caller closes (it goes with its closing)."""
    out = tempfile.TemporaryFile()  # noqa: SIM115 (the caller's to close)
    try:
        with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as archive:
            for folder, files in sources.items():
                with files.lock:
                    add_to(archive, files, folder)
        out.seek(0)
    except BaseException:
        out.close()
        raise
    return out


def pack(files: WorkspaceFiles, max_bytes: int) -> bytes:
    """The workspace's zip as bytes, for a receiver that takes at most ``max_bytes`` (TooLargeError
    past it)."""
    with packed({"": files}) as out:
        size = os.fstat(out.fileno()).st_size
        if size > max_bytes:
            raise TooLargeError(f"the workspace's zip is {size} bytes, over the limit of {max_bytes}")
        return out.read()


def add_to(archive: zipfile.ZipFile, files: WorkspaceFiles, folder: str = "") -> None:
    for entry in files.tree().files:
        with ExitStack() as stack:
            try:
                found = stack.enter_context(files.opened(entry.path))
            except (BadPathError, OSError):
                continue  # a link now, or gone or unreadable since the tree listed it
            if found is not None:
                _add(archive, folder + entry.path, *found)


def _add(archive: zipfile.ZipFile, name: str, fd: int, status: os.stat_result) -> None:
    """The open file as the entry ``name``: its size as it was opened, no byte more; deflated
    unless its first chunk shows that deflate would not shrink it."""
    when = min(max(time.localtime(status.st_mtime)[:6], EARLIEST), LATEST)
    info = zipfile.ZipInfo(name, when)
    info.external_attr = (status.st_mode & 0xFFFF) << 16
    info.file_size = status.st_size  # zipfile picks ZIP64 from it
    first = os.read(fd, min(READ_CHUNK, status.st_size))
    shrinks = len(first) < SMALL or len(zlib.compress(first, 1)) < STORED_ABOVE * len(first)
    info.compress_type = zipfile.ZIP_DEFLATED if shrinks else zipfile.ZIP_STORED
    left = status.st_size - len(first)
    with archive.open(info, "w") as entry:
        entry.write(first)
        while left > 0:
            chunk = os.read(fd, min(READ_CHUNK, left))
            if not chunk:
                break
            entry.write(chunk)
            left -= len(chunk)


def unpack(files: WorkspaceFiles, data: bytes) -> list[str]:
    """Write the zip's files into the workspace (folders are made as needed); the paths written."""
    contents = _contents(files, data)
    with files.lock:
        for relative in contents:
            try:
                found = files.probe(relative)
            except TakenError as exc:
                raise BadArchiveError(f"zip entry {exc}") from None
            if found is not None and stat.S_ISDIR(found.st_mode):
                raise BadArchiveError(f"{relative}: a folder of that name is in the workspace")
        files.check_room({relative: len(raw) for relative, raw in contents.items()})
        for relative, raw in contents.items():
            files.put(relative, raw)
    return sorted(contents)


def replace(files: WorkspaceFiles, data: bytes) -> list[str]:
    """Make the workspace hold exactly the zip's files: checked as ``unpack`` checks them (against
    the workspace's limits, as if it were empty) before anything changes; then every file of the
    tree that the zip does not hold is removed, with the folders left empty, and the zip's files
    are written. Names the tree does not list (hidden ones, links) are left alone. The paths written."""
    contents = _contents(files, data)
    with files.lock:
        tree = files.tree()
        going = {entry.path for entry in tree.files if entry.path not in contents}
        for relative in contents:  # before anything changes
            _check_replacing(files, relative, going)
        for relative in going:
            _remove(files, relative, "file")
        for entry in reversed(tree.entries):  # deepest first: a folder after what it held
            if entry.kind == "dir":  # a file of the zip where it is: it goes, else only if emptied
                _remove(files, entry.path, "folder" if entry.path in contents else "emptied")
        for relative, raw in contents.items():
            files.put(relative, raw)
    return sorted(contents)


def _check_replacing(files: WorkspaceFiles, relative: str, going: set[str]) -> None:
    """BadArchiveError for a link on the way to ``relative`` (or there), or something on its way
    that is not a folder and does not go (a file the tree lists does)."""
    parts = files.parts(relative)
    top = open_root(files.root)
    if top is None:
        return
    try:
        folder, depth = descend(top, parts[:-1], relative)
    except BadPathError as exc:
        raise BadArchiveError(f"zip entry {exc}") from None
    except NotAFolderError as exc:
        taken = "/".join(parts[: exc.depth + 1])
        if taken in going:
            return
        raise BadArchiveError(f"zip entry {relative!r}: {taken} is not a folder") from None
    finally:
        os.close(top)
    try:
        found = lstat_in(folder, parts[-1]) if depth == len(parts) - 1 else None
    finally:
        os.close(folder)
    if found is not None and stat.S_ISLNK(found.st_mode):
        raise BadArchiveError(f"zip entry {through_link(relative)}")


def _remove(files: WorkspaceFiles, relative: str, what: Literal["file", "folder", "emptied"]) -> None:
    """Remove a file, a folder with all in it, or a folder if it is empty; nothing if it is gone."""
    parts = files.parts(relative)
    with files.folder(parts[:-1], relative, "read") as folder:
        if folder is None:
            return
        try:
            if what == "file":
                os.unlink(parts[-1], dir_fd=folder)
            elif what == "folder":
                remove_folder(folder, parts[-1], relative)
            else:
                os.rmdir(parts[-1], dir_fd=folder)
        except (FileNotFoundError, IsADirectoryError, NotADirectoryError):
            pass
        except OSError as exc:
            if exc.errno != errno.ENOTEMPTY:
                raise


def _contents(files: WorkspaceFiles, data: bytes) -> dict[str, bytes]:
    """The zip's files, each checked and read within the workspace's limits."""
    limits = files.limits
    try:
        archive = zipfile.ZipFile(io.BytesIO(data))
    except (zipfile.BadZipFile, ValueError) as exc:
        raise BadArchiveError(f"the upload is not a zip file: {exc}") from None
    with archive:
        infos = archive.infolist()
        if len(infos) > limits.max_files:
            raise TooLargeError(
                f"the zip holds {len(infos)} entries, over the workspace's limit of {limits.max_files}"
            )
        chosen = [info for info in infos if _checked(info, limits.max_file_bytes)]
        declared = sum(info.file_size for info in chosen)
        if declared > limits.max_workspace_bytes:
            raise TooLargeError(
                f"the zip's files declare {declared} bytes, over the workspace's limit of "
                f"{limits.max_workspace_bytes}"
            )
        return _read_all(archive, chosen, limits.max_file_bytes, limits.max_workspace_bytes)


def _checked(info: zipfile.ZipInfo, max_file_bytes: int) -> bool:
    """Whether the entry is a file to write (False: a folder); BadArchiveError when it is refused."""
    name = info.filename
    relative = name.removesuffix("/") if info.is_dir() else name
    try:
        parts_of(relative)
    except BadPathError as exc:
        raise BadArchiveError(f"zip entry {name!r}: {exc}") from None
    mode = info.external_attr >> 16
    if stat.S_ISLNK(mode):
        raise BadArchiveError(f"zip entry {name!r} is a symbolic link; a workspace holds files only")
    if info.flag_bits & 0x1:
        raise BadArchiveError(f"zip entry {name!r} is encrypted")
    if info.is_dir():
        return False
    if info.file_size > max_file_bytes:
        raise TooLargeError(
            f"zip entry {name!r} declares {info.file_size} bytes, over the limit of {max_file_bytes} per file"
        )
    return True


def _read_all(
    archive: zipfile.ZipFile, chosen: list[zipfile.ZipInfo], max_file_bytes: int, max_total_bytes: int
) -> dict[str, bytes]:
    contents: dict[str, bytes] = {}
    total = 0
    for info in chosen:
        if info.filename in contents:
            raise BadArchiveError(f"zip entry {info.filename!r} is there twice")
        raw = _read_bounded(archive, info, max_file_bytes)
        total += len(raw)
        if total > max_total_bytes:
            raise TooLargeError(
                f"the zip's files inflate to more than {max_total_bytes} bytes, the workspace's limit"
            )
        try:
            decode_text(info.filename, raw)
        except NotTextError as exc:
            raise NotTextError(f"zip entry {exc}; only text files go in a workspace") from None
        contents[info.filename] = raw
    for relative in contents:
        folder = relative.rpartition("/")[0]
        while folder:
            if folder in contents:
                raise BadArchiveError(f"zip entry {folder!r} is a file and a folder of {relative!r}")
            folder = folder.rpartition("/")[0]
    return contents


def _read_bounded(archive: zipfile.ZipFile, info: zipfile.ZipInfo, limit: int) -> bytes:
    """The entry's bytes, reading at most one byte past ``limit`` whatever its header declares."""
    chunks: list[bytes] = []
    read = 0
    try:
        with archive.open(info) as entry:
            while read <= limit:
                chunk = entry.read(min(READ_CHUNK, limit + 1 - read))
                if not chunk:
                    break
                chunks.append(chunk)
                read += len(chunk)
    except (zipfile.BadZipFile, EOFError, OSError, NotImplementedError, RuntimeError) as exc:
        # A lying header fails the CRC check (BadZipFile); an unknown method is NotImplementedError.
        raise BadArchiveError(f"zip entry {info.filename!r} cannot be read: {exc}") from None
    if read > limit:
        raise TooLargeError(f"zip entry {info.filename!r} inflates past {limit} bytes, the limit per file")
    return b"".join(chunks)
