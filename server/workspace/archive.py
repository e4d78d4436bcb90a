"""A workspace as one zip, out and in.

Out: every file the tree lists, under its path. In: every entry is checked before anything is
written, and one bad entry refuses the whole upload: a name that is not a workspace path (``..``,
absolute, a backslash), a symbolic link, an encrypted entry, a name given twice, more entries than
the workspace may hold, an entry or a total over the limits by its declared size or by what it
really inflates to (a zip bomb lies in its header; the reading stops one byte past the limit), and
content that is not UTF-8 text.
"""

from __future__ import annotations

import io
import shutil
import stat
import zipfile
from pathlib import PurePosixPath

from .errors import BadArchiveError, BadPathError, NotTextError, TakenError, TooLargeError
from .files import WorkspaceFiles, check_parents, decode_text, write_atomic
from .paths import confine, parts_of

READ_CHUNK = 64 * 1024


def pack(files: WorkspaceFiles, folder: str = "") -> bytes:
    """The workspace's files in a zip, each under ``folder`` + its path."""
    buffer = io.BytesIO()
    with files.lock, zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as archive:
        add_to(archive, files, folder)
    return buffer.getvalue()


def add_to(archive: zipfile.ZipFile, files: WorkspaceFiles, folder: str = "") -> None:
    for entry in files.tree().files:
        path = files.root / entry.path
        try:
            archive.write(path, folder + entry.path)
        except OSError:
            continue  # removed while the zip was made


def unpack(files: WorkspaceFiles, data: bytes) -> list[str]:
    """Write the zip's files into the workspace (folders are made as needed); the paths written."""
    contents = _contents(files, data)
    with files.lock:
        targets = {relative: confine(files.root, relative) for relative in contents}
        for relative, target in targets.items():
            if target.is_dir():
                raise BadArchiveError(f"{relative}: a folder of that name is in the workspace")
            try:
                check_parents(files.root, target, relative)
            except TakenError as exc:
                raise BadArchiveError(f"zip entry {exc}") from None
        files.check_room({relative: len(raw) for relative, raw in contents.items()})
        for relative, raw in contents.items():
            write_atomic(targets[relative], raw)
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
        # Before anything changes: no link on the way to a file of the zip, and nothing the tree
        # does not list where one of its folders goes.
        for relative in contents:
            try:
                confine(files.root, relative)
            except BadPathError as exc:
                raise BadArchiveError(f"zip entry {exc}") from None
            for parent in list(PurePosixPath(relative).parents)[:-1]:
                path = files.root / parent
                if path.exists() and not path.is_dir() and parent.as_posix() not in going:
                    raise BadArchiveError(f"zip entry {relative!r}: {parent.as_posix()} is not a folder")
        for relative in going:
            confine(files.root, relative).unlink(missing_ok=True)
        for entry in reversed(tree.entries):  # deepest first: a folder after what it held
            if entry.kind != "dir":
                continue
            folder = confine(files.root, entry.path)
            if entry.path in contents:  # a file of the zip goes where this folder is
                shutil.rmtree(folder)
            elif not any(folder.iterdir()):  # emptied
                folder.rmdir()
        for relative, raw in contents.items():
            write_atomic(confine(files.root, relative), raw)
    return sorted(contents)


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
            raise TooLargeError(f"the zip's files declare {declared} bytes, over the workspace's limit of "
                                f"{limits.max_workspace_bytes}")  # fmt: skip
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
