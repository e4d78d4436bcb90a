"""``<param from="file.yaml"/>`` in a ``<node>``: ROS 2's parameters file (``node_name:
ros__parameters: ...``, ``/**`` for every node, namespaced names), read when the launch file is,
so a file that is missing or does not parse stops the launch before any node starts, with the
launch file's line and the parameters file's own.

A relative path is taken from the launch file's folder. (launch_ros opens it as given, so
relative to the folder ``ros2 launch`` was started in; a lab's server has no such folder a
student chose, and ``$(dirname)/file.yaml`` means the same in both.) A launch confined to a
workspace reads no file outside it: one elsewhere is refused as a missing one is.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from node_runtime.params_file import ParamsFile, ParamsFileError, read_params_file


def load_param_file(text: str, launch_file: str, may_read: Callable[[Path], bool]) -> ParamsFile | str:
    """The parameters file ``text`` names, seen from ``launch_file``; or what is wrong with it."""
    if not text.strip():
        return '<param from=""> names no file'
    path = Path(text)
    if not path.is_absolute():
        path = Path(launch_file).parent / path
    if not may_read(path) or not path.is_file():
        return f"parameters file not found: {path}"
    try:
        return read_params_file(path)
    except ParamsFileError as exc:
        return f"parameters file {exc}"


__all__ = ["load_param_file"]
