"""A package's folder by name. The lab has no install space: a package's share folder and prefix
are the folder its ``launch/`` folder and its files are in (its source folder for the
workspace's packages), the workspace being ``$ROS2LAB_WORKSPACE``."""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from node_runtime.ament.index import PackageIndex

WORKSPACE_ENV = "ROS2LAB_WORKSPACE"  # the node runner's (node_runtime/ament/workspace.py)


class PackageNotFoundError(KeyError):
    """No package of that name among the lab's and the workspace's."""


def _index() -> PackageIndex:
    from node_runtime.ament.index import PackageIndex  # the lab's packages and the workspace's, found afresh

    workspace = os.environ.get(WORKSPACE_ENV)
    return PackageIndex(workspace=Path(workspace) if workspace else None)


def get_package_share_directory(package_name: str, print_warning: bool = True) -> str:
    index = _index()
    try:
        return str(index.share_dir(package_name))
    except LookupError as exc:
        raise PackageNotFoundError(
            str(exc.args[0]) if exc.args else f"package '{package_name}' not found"
        ) from None


def get_package_share_path(package_name: str, print_warning: bool = True) -> Path:
    return Path(get_package_share_directory(package_name, print_warning))


def get_package_prefix(package_name: str) -> str:
    return get_package_share_directory(package_name)


def get_packages_with_prefixes() -> dict[str, str]:
    index = _index()
    return {name: str(index.share_dir(name)) for name in index.names()}


__all__ = [
    "PackageNotFoundError",
    "get_package_prefix",
    "get_package_share_directory",
    "get_package_share_path",
    "get_packages_with_prefixes",
]
