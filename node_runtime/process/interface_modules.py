"""A node process imports a workspace's interface packages as rclpy imports generated ones:
``from tutorial_interfaces.msg import Num``, ``from tutorial_interfaces.srv import AddThreeInts``,
``from my_action_interfaces.action import Fibonacci``.

A finder at the front of ``sys.meta_path`` answers for ``<pkg>``, ``<pkg>.msg``, ``.srv`` and ``.action``
of each interface package of the workspace the lab gives its node processes (``$ROS2LAB_WORKSPACE``,
read on the first import that could be one), and for nothing else: the lab's own message packages
and every other module are found as before. A type whose definition cannot load is an ImportError
naming its file and line when a node imports it; the package's other types import.
"""

from __future__ import annotations

import importlib.abc
import importlib.machinery
import importlib.util
import os
import sys
from collections.abc import Sequence
from pathlib import Path
from types import ModuleType
from typing import Any

from node_runtime.ament.interfaces import InterfacePackage, WorkspaceInterfaces, workspace_interfaces
from node_runtime.ament.workspace import WORKSPACE_ENV
from node_runtime.msgs import catalog
from node_runtime.msgs._action import action_classes
from node_runtime.msgs._base import message_class, service_classes
from node_runtime.msgs.definitions import lab_definitions

KINDS = ("msg", "srv", "action")
LAB_PACKAGES = frozenset(n.split("/")[0] for n in [*lab_definitions().messages, *lab_definitions().services])


def _types_of(reader: WorkspaceInterfaces, package: str, kind: str) -> dict[str, Any]:
    """Class name → class, for the package's types of ``kind`` that loaded."""
    added = catalog.added(reader.source)
    prefix = f"{package}/{kind}/"
    if kind == "msg":
        return {n.rsplit("/", 1)[1]: message_class(n) for n in added.messages if n.startswith(prefix)}
    if kind == "action":
        actions = action_classes()
        return {n.rsplit("/", 1)[1]: actions[n] for n in added.actions if n.startswith(prefix)}
    services = service_classes()  # not an action's own services (pkg/action/Name_SendGoal)
    return {n.rsplit("/", 1)[1]: services[n] for n in added.services if n.startswith(prefix)}


class _Loader(importlib.abc.Loader):
    def __init__(self, reader: WorkspaceInterfaces, package: InterfacePackage, kind: str | None) -> None:
        self.reader, self.package, self.kind = reader, package, kind

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> ModuleType | None:
        return None  # the default module

    def exec_module(self, module: ModuleType) -> None:
        if self.kind is None:
            return
        types = _types_of(self.reader, self.package.name, self.kind)
        vars(module).update(types)
        module.__all__ = sorted(types)  # type: ignore[attr-defined]
        reader, package, kind = self.reader, self.package, self.kind

        def __getattr__(name: str) -> Any:
            problem = reader.problem_of(f"{package.name}/{kind}/{name}")
            if problem is not None:
                raise ImportError(problem, name=module.__name__)
            raise AttributeError(f"module {module.__name__!r} has no attribute {name!r}")

        module.__getattr__ = __getattr__  # type: ignore[method-assign]


class InterfaceFinder(importlib.abc.MetaPathFinder):
    """Finds the modules of a workspace's interface packages (read on first need)."""

    def __init__(self, workspace: Path) -> None:
        self.workspace = workspace
        self._reader: WorkspaceInterfaces | None = None

    def _package(self, name: str) -> tuple[WorkspaceInterfaces, InterfacePackage] | None:
        if name in LAB_PACKAGES:
            return None  # the lab's own message packages (client/) stay what they are
        if self._reader is None:
            self._reader = workspace_interfaces(self.workspace)
        package = self._reader.packages.get(name)
        return None if package is None else (self._reader, package)

    def find_spec(
        self, fullname: str, path: Sequence[str] | None, target: ModuleType | None = None
    ) -> importlib.machinery.ModuleSpec | None:
        parts = fullname.split(".")
        if len(parts) > 2 or (len(parts) == 2 and parts[1] not in KINDS):
            return None
        found = self._package(parts[0])
        if found is None:
            return None
        reader, package = found
        kind = parts[1] if len(parts) == 2 else None
        spec = importlib.util.spec_from_loader(
            fullname, _Loader(reader, package, kind), is_package=kind is None
        )
        if spec is not None and kind is None:
            python_dir = package.path / package.name  # an ament_cmake_python package's own modules
            spec.submodule_search_locations = [str(python_dir)] if python_dir.is_dir() else []
        return spec


def install(environ: os._Environ[str] | dict[str, str] | None = None) -> InterfaceFinder | None:
    """Put the finder first on ``sys.meta_path`` for ``$ROS2LAB_WORKSPACE``, if it is set."""
    workspace = (os.environ if environ is None else environ).get(WORKSPACE_ENV)
    if not workspace:
        return None
    finder = InterfaceFinder(Path(workspace))
    sys.meta_path.insert(0, finder)
    return finder
