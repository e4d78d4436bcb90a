"""Which launch file a request names: a package's launch file by name, or (on a lab that serves
its user alone) any path.

Where the lab serves others (``Settings.confines_paths``: a class's worlds, a lab beyond loopback)
a launch file is a file of the world's own packages: a name in a package's ``launch/`` folder
(built-in or the workspace's), or a path inside the workspace. Anything else, an absolute path,
a ``..`` or a link that leads out, gets the one answer a missing file gets, so the answer tells
nothing of what exists elsewhere on the server.
"""

from __future__ import annotations

from pathlib import Path, PurePath

from node_runtime.ament.index import PackageIndex


class LaunchFileNotFoundError(LookupError):
    """The request names no launch file of this world's packages."""


def launch_file(packages: PackageIndex, package: str | None, file: str, *, confined: bool) -> Path:
    """The launch file ``file`` (in ``package``'s launch folder when a package is named)."""
    if not confined:
        return packages.share_dir(package) / "launch" / file if package else Path(file)
    if package:
        root = packages.share_dir(package)
        path = _within(root, root / "launch", file, plain_name=True)
    elif packages.workspace is not None:
        path = _within(packages.workspace, packages.workspace, file, plain_name=False)
    else:
        path = None
    if path is None:
        raise LaunchFileNotFoundError(
            f"no launch file {file[:200]!r} in this world's packages: name a package and one of its "
            "launch files, or give a path inside the workspace"
        )
    return path


def _within(root: Path, folder: Path, file: str, *, plain_name: bool) -> Path | None:
    """``folder / file`` if it is a file that stays inside ``root`` once links are followed."""
    parts = PurePath(file).parts
    if not parts or PurePath(file).is_absolute() or "\\" in file or "\0" in file:
        return None
    if ".." in parts or (plain_name and len(parts) != 1):
        return None
    path = folder / file
    try:
        inside = path.is_file() and path.resolve().is_relative_to(root.resolve())
    except OSError:  # a name too long, a folder not readable
        return None
    return path if inside else None
