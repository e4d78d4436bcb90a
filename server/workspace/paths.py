"""Paths inside a workspace: POSIX, relative, made of names ROS and colcon accept, never leaving
the folder. Checked on the text first (no ``..``, no absolute path, no backslash, no NUL, no hidden
name), then on the disk (no symlink on the way: a link could lead out)."""

from __future__ import annotations

import re
from pathlib import Path

from .errors import BadPathError

MAX_PATH_CHARS = 1024
MAX_NAME_CHARS = 255
MAX_DEPTH = 16
# A file or folder name: letters, digits, ``_``, ``-`` and dots, not starting with a dot or a dash
# (colcon skips hidden folders; a leading dash reads as an option on a command line).
NAME = re.compile(r"^[A-Za-z0-9_][A-Za-z0-9_.\-]*$")


def parts_of(relative: str) -> tuple[str, ...]:
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
    if len(parts) > MAX_DEPTH:
        raise BadPathError(f"a path deeper than {MAX_DEPTH} folders")
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


def confine(root: Path, relative: str) -> Path:
    """The path ``relative`` names inside ``root``, with no symlink on the way (it may not exist)."""
    parts = parts_of(relative)
    path = root
    for part in parts:
        path = path / part
        if path.is_symlink():
            raise BadPathError(
                f"{relative!r} goes through a symbolic link, which could lead out of the workspace"
            )
    if not path.resolve().is_relative_to(root.resolve()):
        raise BadPathError(f"{relative!r} leads out of the workspace")
    return path


def relative_of(root: Path, path: Path) -> str:
    return path.relative_to(root).as_posix()
