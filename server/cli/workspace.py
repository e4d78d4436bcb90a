"""Which workspace ``ros2lab run`` and ``ros2lab pkg`` read: the one given, or the lab's.

In order: ``--workspace``, then ``$ROS2LAB_WORKSPACE``, then the folder the running lab uses when
it is on this machine (``GET /api/workspace`` names it and it exists here), then ``./workspace``.
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

from server.cli.errors import CliError
from server.cli.plain_get import LabGetter

WORKSPACE_ENV = "ROS2LAB_WORKSPACE"
FALLBACK = Path("workspace")


def add_workspace_option(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--workspace",
        default=None,
        help=f"folder of your own packages (default: ${WORKSPACE_ENV}, else the running lab's when it is "
        "on this machine, else ./workspace)",
    )


def lab_workspace(client: LabGetter) -> Path | None:
    """The lab's workspace folder, if the lab says one and it is on this machine."""
    try:
        answer = client.get("/api/workspace")
    except CliError:  # no lab, or one older than this CLI
        return None
    path = answer.get("path") if isinstance(answer, dict) else None
    return Path(path) if isinstance(path, str) and Path(path).is_dir() else None


def workspace_of(args: argparse.Namespace, client: LabGetter) -> Path:
    given = getattr(args, "workspace", None) or os.environ.get(WORKSPACE_ENV)
    if given:
        return Path(given)
    return lab_workspace(client) or FALLBACK
