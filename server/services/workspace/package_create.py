"""A new package as ``ros2 pkg create`` makes it: its rules for names, its folders and its files
(server.packages.templates), written under a destination folder. ``ros2lab pkg create`` and the
workspace API's ``POST /api/workspace/packages`` both write packages through here."""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

from server.packages.templates import PackageSpec, package_files
from server.services.workspace.errors import BadPackageError, TakenError
from server.services.workspace.files import WorkspaceFiles, write_atomic

NAME = re.compile(r"^[a-z][a-z0-9_]*$")  # REP 144's package names
NODE_NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
SOURCE = "src"  # where new packages go in a workspace, as colcon's layout has them


def package_refusal(
    name: str, build_type: str, node_name: str | None, dependencies: Sequence[str] = ()
) -> str | None:
    """What ``ros2 pkg create`` would say against these options, or None."""
    if not NAME.match(name):
        return (
            f"Invalid package name '{name}': it must start with a lowercase letter and "
            "hold only lowercase letters, digits and underscores"
        )
    if build_type == "ament_python" and name == "test":
        return "Aborted since 'ament_python' packages can't be named 'test'. Please choose a different package name."
    if node_name is not None and not NODE_NAME.match(node_name):
        return f"Invalid node name '{node_name}': it must be a Python identifier"
    bad = [d for d in dependencies if not NAME.match(d)]
    if bad:
        return f"Invalid dependency name '{bad[0]}': a package name as REP 144 has them"
    return None


def folders_of(spec: PackageSpec) -> list[str]:
    """The folders ``ros2 pkg create`` makes first, inside the package folder ('' is the package's own)."""
    return ["", "src", f"include/{spec.name}"] if spec.build_type == "ament_cmake" else [""]


def write_package(
    package_dir: Path, spec: PackageSpec, report: Callable[[str, Path], None] | None = None
) -> list[Path]:
    """Make the package's folders and files in ``package_dir`` (``report`` hears each, as
    ``ros2 pkg create`` prints them); the files written."""
    for folder in folders_of(spec):
        path = package_dir / folder if folder else package_dir
        if report is not None:
            report("creating folder", path)
        path.mkdir(parents=True, exist_ok=True)
    written = []
    for relative, text in package_files(spec).items():
        path = package_dir / relative
        if report is not None:
            report("creating", path)
        write_atomic(path, text.encode("utf-8"))
        written.append(path)
    return written


@dataclass(frozen=True)
class CreatedPackage:
    name: str
    path: str  # the package's folder in the workspace
    files: list[str]  # every file written, in the workspace


def create_package(files: WorkspaceFiles, spec: PackageSpec) -> CreatedPackage:
    """The package in ``src/<name>`` of the workspace: refused (and nothing written) for a bad
    name, a name taken, or no room in the workspace."""
    refusal = package_refusal(spec.name, spec.build_type, spec.node_name, spec.dependencies)
    if refusal is not None:
        raise BadPackageError(refusal)
    folder = f"{SOURCE}/{spec.name}"
    texts = {f"{folder}/{relative}": text for relative, text in package_files(spec).items()}
    with files.lock:
        if files.probe(folder) is not None:
            raise TakenError(f"{folder} exists already: remove it or choose another package name")
        files.check_room({path: len(text.encode("utf-8")) for path, text in texts.items()})
        for inside in folders_of(spec):
            files.make_folder(f"{folder}/{inside}" if inside else folder)
        for path, text in texts.items():
            files.put(path, text.encode("utf-8"))
    return CreatedPackage(spec.name, folder, list(texts))
