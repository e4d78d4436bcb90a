"""The lab's launch names: ``rocket``, ``fly`` and ``all`` name a launch file of its packages."""

from __future__ import annotations

from pathlib import Path

from node_runtime.ament.index import PackageIndex

LAUNCH_ALIASES = {
    "rocket": ("rocketship", "rocket.launch"),
    "fly": ("flightcontroller", "fly.launch"),
    "all": ("lab", "all.launch"),
}


def resolve_launch(launch: str, packages: PackageIndex) -> Path:
    """``rocket``, ``fly``, ``all`` or a path → the launch file's path."""
    if launch in LAUNCH_ALIASES:
        pkg, file = LAUNCH_ALIASES[launch]
        return packages.share_dir(pkg) / "launch" / file
    return Path(launch)
