"""Reading a ``.launch.py`` file: import it as a module and call its ``generate_launch_description()``."""

from __future__ import annotations

import importlib.util
import itertools
from pathlib import Path
from types import ModuleType
from typing import Any

_numbers = itertools.count(1)


class InvalidPythonLaunchFileError(Exception):
    """A Python launch file that cannot be used: the message names the file."""


def load_python_launch_file_as_module(python_launch_file_path: str) -> ModuleType:
    path = Path(python_launch_file_path)
    if not path.is_file():
        raise InvalidPythonLaunchFileError(f"{path}: launch file not found")
    # Not a module name the launch file could import by: two files of one name stay apart.
    spec = importlib.util.spec_from_file_location(f"_launch_file_{next(_numbers)}", str(path))
    if spec is None or spec.loader is None:
        raise InvalidPythonLaunchFileError(f"{path}: cannot be loaded as Python")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def get_launch_description_from_python_launch_file(python_launch_file_path: str) -> Any:
    from launch.launch_description import LaunchDescription

    module = load_python_launch_file_as_module(python_launch_file_path)
    generate = getattr(module, "generate_launch_description", None)
    if generate is None:
        raise InvalidPythonLaunchFileError(
            f"{python_launch_file_path}: it has no generate_launch_description() function"
        )
    if not callable(generate):
        raise InvalidPythonLaunchFileError(
            f"{python_launch_file_path}: generate_launch_description is not a function"
        )
    description = generate()
    if not isinstance(description, LaunchDescription):
        raise InvalidPythonLaunchFileError(
            f"{python_launch_file_path}: generate_launch_description() returned "
            f"{type(description).__name__}, not a launch.LaunchDescription"
        )
    return description
