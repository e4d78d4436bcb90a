"""Students' packages: a ROS-style workspace whose node files and launch files join the lab.

A workspace is a folder with ``src/<package>/`` folders (or the packages right in it). Every
``*.py`` file in a package (outside ``launch/`` and ``test*/``) is an executable, under both
its file name and its stem (``keyboard_manager.py`` and ``keyboard_manager``), the way the
lab's CMake and ament_python packages name them; ``launch/`` holds launch files. A student
package with the name of a built-in one overlays it: its executables win, and its launch
folder is used when it has one. Files are read again at every launch, so edits need no restart.
"""

from __future__ import annotations

import importlib.util
import itertools
import logging
import sys
import time
import traceback
from collections.abc import Callable
from pathlib import Path
from types import ModuleType
from typing import Any, cast

from server.bus import Node

log = logging.getLogger("workspace")
COMPAT_DIR = Path(__file__).resolve().parent.parent / "compat"
SKIP_FILES = {"setup.py", "__init__.py", "conftest.py"}
_module_ids = itertools.count(1)


class NodeFileError(Exception):
    """A student's node file that cannot be loaded; says which file, line and why."""


def packages_in(workspace: Path) -> dict[str, Path]:
    """Package name → folder, for ``workspace/src/*`` (or ``workspace/*`` without a src/)."""
    root = workspace / "src" if (workspace / "src").is_dir() else workspace
    if not root.is_dir():
        return {}
    return {p.name: p for p in sorted(root.iterdir()) if p.is_dir() and not p.name.startswith((".", "_"))}


def executables_in(package_dir: Path) -> dict[str, Path]:
    exes: dict[str, Path] = {}
    for path in sorted(package_dir.rglob("*.py")):
        parts = path.relative_to(package_dir).parts
        if path.name in SKIP_FILES or any(
            p == "launch" or p.startswith(("test", ".", "_")) for p in parts[:-1]
        ):
            continue
        exes.setdefault(path.name, path)
        exes.setdefault(path.stem, path)
    return exes


class _CooperativeTime:
    """``time`` for node files, except that ``sleep`` does not block the app's loop.

    The handout's drone skeleton sleeps 10 s in its constructor to let the simulator start; on
    this bus that would freeze every node, and the simulator is already running.
    """

    def __init__(self, where: str) -> None:
        self._where = where

    def __getattr__(self, name: str) -> Any:
        return getattr(time, name)

    def sleep(self, seconds: float) -> None:
        log.warning(
            "%s: time.sleep(%s) skipped: it would block every node (use create_timer to wait)",
            self._where,
            seconds,
        )


def _location_in(path: Path, exc: BaseException) -> str:
    if isinstance(exc, SyntaxError) and exc.lineno is not None:
        return f"{path}:{exc.lineno}"
    frames = [f for f in traceback.extract_tb(exc.__traceback__) if Path(f.filename) == path]
    return f"{path}:{frames[-1].lineno}" if frames else str(path)


def load_module(path: Path) -> ModuleType:
    """Import a node file afresh (with rclpy and the message packages available)."""
    if str(COMPAT_DIR) not in sys.path:
        sys.path.insert(0, str(COMPAT_DIR))
    name = f"_lab_workspace_{next(_module_ids)}_{path.stem.replace('.', '_')}"
    spec = importlib.util.spec_from_file_location(name, path)
    if spec is None or spec.loader is None:
        raise NodeFileError(f"{path}: not a Python file")
    module = importlib.util.module_from_spec(spec)
    try:
        spec.loader.exec_module(module)
    except BaseException as exc:  # SystemExit from a script's top level included
        raise NodeFileError(f"{_location_in(path, exc)}: {type(exc).__name__}: {exc}") from None
    for attr, value in list(vars(module).items()):
        if value is time:
            setattr(module, attr, _CooperativeTime(str(path)))
        elif value is time.sleep:
            setattr(module, attr, _CooperativeTime(str(path)).sleep)
    return module


def node_factory(path: Path) -> Callable[[], Node]:
    """A factory for the one Node subclass the file defines; errors name the file and line."""

    def make() -> Node:
        module = load_module(path)
        classes = [
            v
            for v in vars(module).values()
            if isinstance(v, type) and issubclass(v, Node) and v.__module__ == module.__name__
        ]
        if len(classes) != 1:
            found = ", ".join(c.__name__ for c in classes) or "none"
            raise NodeFileError(f"{path}: a node file must define exactly one Node subclass (found: {found})")
        try:
            return cast(Callable[[], Node], classes[0])()  # a lab node takes no arguments
        except Exception as exc:
            raise NodeFileError(
                f"{_location_in(path, exc)}: {classes[0].__name__}() raised {type(exc).__name__}: {exc}"
            ) from exc

    return make
