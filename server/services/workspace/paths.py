"""Paths inside a workspace: POSIX, relative, made of names ROS and colcon accept, never leaving
the folder. Checked here on the text (no ``..``, no absolute path, no backslash, no NUL, no hidden
name, no deeper than the limit); on the disk, the folders are then opened one name at a time with
no symbolic link on the way (``handles.py``): a link could lead out."""

from __future__ import annotations

import re

from server.host.settings.lab import WORKSPACE_DEPTH
from server.services.workspace.errors import BadPathError

MAX_PATH_CHARS = 1024
MAX_NAME_CHARS = 255
MAX_DEPTH = WORKSPACE_DEPTH  # WorkspaceLimits.max_depth's default
# A file or folder name: letters, digits, ``_``, ``-`` and dots, not starting with a dot or a dash
# (colcon skips hidden folders; a leading dash reads as an option on a command line).
NAME = re.compile(r"^[A-Za-z0-9_][A-Za-z0-9_.\-]*$")


def parts_of(relative: str, max_depth: int = MAX_DEPTH) -> tuple[str, ...]:
    """The names of a workspace path as sent; BadPathError naming what is wrong with it."""
    if not relative:
        raise BadPathError("an empty path: name a file or folder inside the workspace")
    if len(relative) > MAX_PATH_CHARS:
        raise BadPathError(f"a path longer than {MAX_PATH_CHARS} characters")
    if "\x00" in relative:
        raise BadPathError("a path holding a NUL character")
    if "\\" in relative:
        raise BadPathError(f"a backslash in {relative!r}: paths are POSIX, with '/'")
    if relative.startswith("/"):
        raise BadPathError(f"an absolute path {relative!r}: paths are relative to the workspace")
    parts = tuple(relative.split("/"))
    if len(parts) > max_depth:
        raise BadPathError(f"a path deeper than {max_depth} folders")
    for part in parts:
        if part in ("", ".", ".."):
            raise BadPathError(
                f"{relative!r} holds {part or 'an empty name'!r}: name each folder once, no '.' or '..'"
            )
        if len(part) > MAX_NAME_CHARS:
            raise BadPathError(f"a name longer than {MAX_NAME_CHARS} characters in {relative!r}")
        if not NAME.match(part):
            raise BadPathError(
                f"{part!r} in {relative!r} is not a name the workspace takes: letters, digits, '_', '-' "
                "and '.', not starting with '.' or '-'"
            )
    return parts
