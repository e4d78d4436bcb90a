"""Students' packages: a workspace as colcon sees it, whose executables and launch files join the lab.

A package is a folder with a ``package.xml``, at any depth under the workspace's ``src/`` (or
the workspace itself without a ``src/``), named by its ``<name>``; colcon's rules for what it does
not enter hold (a ``COLCON_IGNORE`` file, ``build/``, ``install/``, ``log/``, hidden folders, and
nothing below a package). Its executables are what ``ros2 run`` would find after ``colcon build``:
an ament_python package's ``console_scripts`` (run as ``module:function`` with the package
importable), an ament_cmake package's ``install(PROGRAMS ...)`` files.

A folder right under ``src/`` with no ``package.xml`` in or below it, or a package with neither a
``setup.py``/``setup.cfg`` nor a ``CMakeLists.txt``, keeps the lab's simple rule: every ``*.py``
file in it (outside ``launch/`` and ``test*/``) is an executable, under both its file name and its
stem (``keyboard_manager.py`` and ``keyboard_manager``). ``launch/`` holds launch files.

A student package with the name of a built-in one overlays it: its executables win, and its
launch folder is used when it has one. A student's file always runs as its own process
(server.host.processes), read afresh at every start, so edits need no restart.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path

from node_runtime.ament.entry_points import EntryPoint, cmake_programs, setup_cfg_scripts, setup_py_scripts
from node_runtime.ament.manifest import MANIFEST, WorkspaceError, read_manifest

# Where a node process finds its workspace (set by whatever starts it: the lab, ``ros2lab run``).
WORKSPACE_ENV = "ROS2LAB_WORKSPACE"
SKIP_FILES = {"setup.py", "__init__.py", "conftest.py"}
NOT_ENTERED = {"build", "install", "log"}  # colcon's own output, next to src/
IGNORE_MARKER = "COLCON_IGNORE"


@dataclass(frozen=True)
class StudentExecutable:
    """One executable of a student's package: a file to run, or an entry point (its module's file)."""

    file: Path
    entry_point: EntryPoint | None = None


@dataclass(frozen=True)
class WorkspacePackage:
    name: str
    path: Path
    build_type: str | None  # None: a folder without a package.xml (the lab's simple rule)

    def executables(self) -> dict[str, StudentExecutable]:
        setup_py, setup_cfg, cmake = (self.path / f for f in ("setup.py", "setup.cfg", "CMakeLists.txt"))
        if self.build_type is None or not (setup_py.is_file() or setup_cfg.is_file() or cmake.is_file()):
            return {name: StudentExecutable(path) for name, path in files_in(self.path).items()}
        if self.build_type == "ament_python" or not cmake.is_file():
            scripts = [
                *(setup_cfg_scripts(setup_cfg) if setup_cfg.is_file() else []),
                *(setup_py_scripts(setup_py) if setup_py.is_file() else []),
            ]
            return {
                s.name: StudentExecutable(
                    module_file(self.path, s.module),
                    EntryPoint(self.path, s.module, s.function, s.name, s.declared_at),
                )
                for s in scripts
            }
        return {
            name: StudentExecutable(file) for name, (file, _where) in cmake_programs(cmake, self.name).items()
        }


@dataclass
class Workspace:
    """The packages found, and what stops a name from being used (a duplicate, a bad package.xml)."""

    packages: dict[str, WorkspacePackage] = field(default_factory=dict)
    problems: dict[str, WorkspaceError] = field(default_factory=dict)  # by the package name it blocks

    def get(self, name: str) -> WorkspacePackage | None:
        if name in self.problems:
            raise self.problems[name]
        return self.packages.get(name)


def module_file(root: Path, module: str) -> Path:
    base = root.joinpath(*module.split("."))
    return base / "__init__.py" if base.is_dir() else base.with_suffix(".py")


def files_in(package_dir: Path) -> dict[str, Path]:
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


def _manifests(root: Path) -> list[Path]:
    """The package folders below ``root``, in colcon's walk (sorted, so the result is stable)."""
    found: list[Path] = []
    for folder, dirs, files in os.walk(root):
        here = Path(folder)
        if IGNORE_MARKER in files and here != root:
            dirs[:] = []
            continue
        if MANIFEST in files and here != root:
            found.append(here)
            dirs[:] = []  # colcon looks no deeper than a package
            continue
        dirs[:] = sorted(
            d for d in dirs if not d.startswith((".", "_")) and not (here == root and d in NOT_ENTERED)
        )
    return found


def find_packages(workspace: Path) -> Workspace:
    root = workspace / "src" if (workspace / "src").is_dir() else workspace
    found = Workspace()
    if not root.is_dir():
        return found
    places: dict[str, Path] = {}
    manifests = _manifests(root)
    for path in manifests:
        try:
            manifest = read_manifest(path / MANIFEST)
        except WorkspaceError as exc:
            found.problems.setdefault(path.name, exc)  # its name is unknown: its folder's name is blocked
            continue
        name = manifest.name
        if name in places:
            found.problems[name] = WorkspaceError(
                str(path / MANIFEST), f"two packages are named '{name}': {places[name]} and {path}"
            )
            continue
        places[name] = path
        found.packages[name] = WorkspacePackage(name, path, manifest.build_type)
    for folder in sorted(root.iterdir()):
        plain = folder.is_dir() and not folder.name.startswith((".", "_")) and folder.name not in NOT_ENTERED
        plain = plain and not (folder / IGNORE_MARKER).exists() and folder.name not in found.problems
        if plain and folder.name not in places and not any(p.is_relative_to(folder) for p in manifests):
            found.packages[folder.name] = WorkspacePackage(folder.name, folder, None)
    for name in found.problems:
        found.packages.pop(name, None)
    return found
