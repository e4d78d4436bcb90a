"""Read a launch file, in the front-end its name asks for, into a ``LaunchDescription``.

XML and YAML in three stages, one module each: ``xml_tree`` (or ``yaml_tree``) reads the file
into an element tree with line numbers and checks it against the schema; ``substitutions`` parses
``$(...)``; ``evaluation`` performs substitutions and conditions, follows includes and collects
the nodes in document order (``values`` types what it reads). A Python file is evaluated in a
process of its own (``python_process``) and folded into the same model (``python_launch``).
Nothing is executed: the result is plain data for the launcher.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path
from types import MappingProxyType

from server.services.launch.description import LaunchDescription, LaunchFileError
from server.services.launch.evaluation import FindPackageShare, evaluate, is_python
from server.services.launch.frontends import load_frontend_tree
from server.services.launch.python_launch import RunPython, evaluate_python_file, include_python_with
from server.services.launch.xml_tree import MAX_FILE_BYTES, load_tree, read_bytes

__all__ = ["MAX_FILE_BYTES", "FindPackageShare", "parse_launch_file", "parse_launch_string"]

_NO_ARGS: Mapping[str, str] = MappingProxyType({})


def parse_launch_file(
    path: str | os.PathLike[str],
    *,
    args: Mapping[str, str] = _NO_ARGS,
    find_package_share: FindPackageShare,
    environ: Mapping[str, str] | None = None,
    roots: tuple[Path, ...] | None = None,
    run_python: RunPython | None = None,
) -> LaunchDescription:
    """Parse a launch file (XML, YAML or, with ``run_python``, Python) and the files it includes
    into one flat ``LaunchDescription``.

    ``args`` plays the role of ``ros2 launch ... name:=value``; every name must be declared by
    the file. ``environ`` (default ``os.environ``) answers ``$(env ...)``. Raises
    ``LaunchFileError`` naming the file and line of the first problem. With ``roots``, a file
    included from outside them is refused as a missing one.
    """
    file = os.fspath(path)
    if is_python(Path(file)):
        if run_python is None:
            raise LaunchFileError(file, 0, "Python launch files are not evaluated here")
        return evaluate_python_file(Path(file), args, find_package_share, run_python, environ, roots)
    try:
        data = read_bytes(Path(file))
    except FileNotFoundError:
        raise LaunchFileError(file, 0, "launch file not found") from None
    except OSError as err:
        raise LaunchFileError(file, 0, f"cannot read launch file: {err.strerror}") from None
    except ValueError as err:  # a NUL byte in the path
        raise LaunchFileError(file[:200], 0, f"not a file path: {err}") from None
    include = include_python_with(run_python) if run_python is not None else None
    return evaluate(load_frontend_tree(data, file), file, args, find_package_share, environ, roots, include)


def parse_launch_string(
    text: str,
    *,
    filename: str = "<string>",
    args: Mapping[str, str] = _NO_ARGS,
    find_package_share: FindPackageShare,
    environ: Mapping[str, str] | None = None,
) -> LaunchDescription:
    """Parse launch XML held in memory; ``filename`` names it in errors and anchors relative includes."""
    return evaluate(
        load_tree(text.encode("utf-8"), filename, "utf-8"), filename, args, find_package_share, environ
    )
