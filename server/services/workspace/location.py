"""Where a class world's workspace lives: the folder of the world's name in the class's
``workspaces_dir``, kept across resets and restarts of the server, removed with the student."""

from __future__ import annotations

import errno
import os
from pathlib import Path

from server.services.workspace.errors import WorkspaceFileError
from server.services.workspace.paths import parts_of
from server.services.workspace.removal import remove_folder as remove_within


def world_workspace(workspaces_dir: Path, world: str) -> Path:
    """The folder of ``world``'s workspace (a world's name is one plain name: no ``/``, no ``..``)."""
    (name,) = parts_of(world)
    return workspaces_dir / name


def world_has_files(workspaces_dir: Path, world: str) -> bool:
    """Whether the world's workspace holds anything (it is made with the first file written)."""
    try:
        with os.scandir(world_workspace(workspaces_dir, world)) as entries:
            return next(entries, None) is not None
    except (FileNotFoundError, NotADirectoryError):
        return False


def remove_world_workspace(workspaces_dir: Path, world: str) -> bool:
    """Remove the world's workspace with everything in it; whether there was one."""
    return remove_folder(world_workspace(workspaces_dir, world))


def remove_folder(folder: Path) -> bool:
    """Remove ``folder`` with everything in it (a link to one: the link alone, never what it
    points at; a link inside it likewise), by a loop however deep it goes; whether there was one.
    OSError when it could not be removed (its callers log it and go on)."""
    if folder.is_symlink():
        folder.unlink()
        return True
    if not folder.is_dir():
        return False
    parent = os.open(folder.parent, os.O_RDONLY | os.O_DIRECTORY | os.O_CLOEXEC)
    try:
        remove_within(parent, folder.name, folder.name)
    except WorkspaceFileError as exc:  # a link or a file in its place, or it kept filling
        raise OSError(errno.ENOTEMPTY, str(exc)) from None
    finally:
        os.close(parent)
    return True
