"""Students' packages: a ROS-style workspace whose node files and launch files join the lab.

A workspace is a folder with ``src/<package>/`` folders (or the packages right in it). Every
``*.py`` file in a package (outside ``launch/`` and ``test*/``) is an executable, under both
its file name and its stem (``keyboard_manager.py`` and ``keyboard_manager``), the way the
lab's CMake and ament_python packages name them; ``launch/`` holds launch files. A student
package with the name of a built-in one overlays it: its executables win, and its launch
folder is used when it has one. A student's file always runs as its own process
(server.processes), read afresh at every start, so edits need no restart.
"""

from __future__ import annotations

import logging
from pathlib import Path

log = logging.getLogger("workspace")
SKIP_FILES = {"setup.py", "__init__.py", "conftest.py"}


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
