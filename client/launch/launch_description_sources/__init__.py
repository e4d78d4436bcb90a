"""Where an included launch description comes from, under ROS 2's names."""

from __future__ import annotations

from typing import Any

from launch.launch_description_sources.launch_description_source import LaunchDescriptionSource
from launch.launch_description_sources.python_launch_file_utilities import (
    InvalidPythonLaunchFileError,
    get_launch_description_from_python_launch_file,
    load_python_launch_file_as_module,
)


class PythonLaunchDescriptionSource(LaunchDescriptionSource):
    """A ``.launch.py`` file."""

    def __init__(self, launch_file_path: Any) -> None:
        super().__init__(launch_file_path, "interpreted python launch file")

    def include(self, context: Any, passed: dict[str, str], action: Any) -> list[Any]:
        from launch.launch_description_sources.launch_description_source import include_python

        return include_python(context, self.resolve(context))


class FrontendLaunchDescriptionSource(LaunchDescriptionSource):
    """An XML or YAML launch file."""

    def __init__(self, launch_file_path: Any, *, parser: Any = None) -> None:
        super().__init__(launch_file_path, "interpreted frontend launch file")

    def include(self, context: Any, passed: dict[str, str], action: Any) -> list[Any]:
        from launch.launch_description_sources.launch_description_source import include_frontend

        return include_frontend(context, self.resolve(context), passed, action)


class AnyLaunchDescriptionSource(LaunchDescriptionSource):
    """Python for a ``.py`` file, else XML or YAML (by its name)."""

    def __init__(self, launch_file_path: Any) -> None:
        super().__init__(launch_file_path, "interpreted launch file")


__all__ = [
    "AnyLaunchDescriptionSource",
    "FrontendLaunchDescriptionSource",
    "InvalidPythonLaunchFileError",
    "LaunchDescriptionSource",
    "PythonLaunchDescriptionSource",
    "get_launch_description_from_python_launch_file",
    "load_python_launch_file_as_module",
]
