"""The lab's own packages come first in a node process: a student's folder on ``sys.path`` never
replaces them.

A node's runner puts the student's folder first on ``sys.path``, as ``python node.py`` and
``ros2 run`` do, so the node's own modules import. A folder of the student's named ``rclpy``,
``std_msgs`` or ``server`` beside the node would then be imported instead of the lab's (the lab's
packages are found after ``sys.path``, by its install's finder). ``pin`` finds where each of the
lab's top-level packages is before any student's folder is on the path, and puts a finder in front
that answers those names from there; the packages themselves are imported only when the node
imports them.
"""

from __future__ import annotations

import importlib.abc
import importlib.machinery
import importlib.util
import sys
from collections.abc import Sequence
from types import ModuleType

# The client's packages: rclpy, the message packages, launch's (client/; top-level in the client wheel,
# where there is no client/ folder to list: tests/processes/test_lab_packages.py keeps them equal).
CLIENT_PACKAGES = (
    "action_msgs",
    "action_tutorials_interfaces",
    "actionlib_msgs",
    "ament_index_python",
    "builtin_interfaces",
    "diagnostic_msgs",
    "example_interfaces",
    "geometry_msgs",
    "keyboard_msgs",
    "launch",
    "launch_ros",
    "launch_xml",
    "launch_yaml",
    "lifecycle_msgs",
    "nav_msgs",
    "rcl_interfaces",
    "rclpy",
    "rosapi_msgs",
    "rosgraph_msgs",
    "sensor_msgs",
    "sensor_msgs_py",
    "service_msgs",
    "shape_msgs",
    "std_msgs",
    "std_srvs",
    "stereo_msgs",
    "tf2_msgs",
    "tf2_ros",
    "trajectory_msgs",
    "turtlesim",
    "type_description_interfaces",
    "unique_identifier_msgs",
    "visualization_msgs",
)
OWN = ("node_runtime", "server", "sim")


def names() -> list[str]:
    """The lab's top-level packages a node process may import: its own and the client's."""
    return [*OWN, *CLIENT_PACKAGES]


class _LabFirst(importlib.abc.MetaPathFinder):
    def __init__(self, specs: dict[str, importlib.machinery.ModuleSpec]) -> None:
        self.specs = specs

    def find_spec(
        self, fullname: str, path: Sequence[str] | None = None, target: ModuleType | None = None
    ) -> importlib.machinery.ModuleSpec | None:
        spec = self.specs.get(fullname)
        if spec is None or spec.origin is None:
            return None
        return importlib.util.spec_from_file_location(
            fullname, spec.origin, submodule_search_locations=spec.submodule_search_locations
        )


def pin() -> None:
    """Answer the lab's top-level names from where they are now, ahead of ``sys.path``."""
    if any(isinstance(finder, _LabFirst) for finder in sys.meta_path):
        return
    specs: dict[str, importlib.machinery.ModuleSpec] = {}
    for name in names():
        spec = sys.modules[name].__spec__ if name in sys.modules else importlib.util.find_spec(name)
        if spec is not None:
            specs[name] = spec
    sys.meta_path.insert(0, _LabFirst(specs))
