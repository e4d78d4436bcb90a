"""The packages a node process can name, ``(pkg, exec)`` → what runs: the lab's own nodes (the
folders of ``server/packages``, where the app is installed) and a student's workspace.

Each lab package is a folder of ``server/packages``; its ``launch/`` folder is what
``$(find-pkg-share PKG)`` names. A client-only install has none of them.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from node_runtime.ament.entry_points import EntryPoint
from node_runtime.ament.manifest import WorkspaceError
from node_runtime.ament.workspace import Workspace, WorkspacePackage, find_packages

if TYPE_CHECKING:  # both import the message types, which finding an executable never needs
    from node_runtime.ament.interfaces import WorkspaceInterfaces
    from node_runtime.bus import Node


def _lab_packages() -> Path:
    """Where the lab's own packages lie: ``server/packages`` beside this runtime, in the repository
    and in the app's install alike. Found by path, importing nothing (a student's folder named
    ``server`` on the path is never looked at); a client-only install has none."""
    return Path(__file__).resolve().parents[2] / "server" / "packages"


HERE = _lab_packages()

# exec name → "module:Class", per package, with the lab's executable names.
BUILTIN: dict[str, dict[str, str]] = {
    "rocketship": {
        "countdown": "server.packages.rocketship.countdown:CountDownNode",
        "main_controller": "server.packages.rocketship.main_controller:MainControllerNode",
        "rocket_engine.py": "server.packages.rocketship.rocket_engine:RocketEngineNode",
        "keyboard_manager.py": "server.packages.rocketship.keyboard_manager:KeyboardManager",
    },
    "keyboard": {"keyboard": "server.packages.keyboard.keyboard:KeyboardNode"},
    "flightcontroller": {
        "position_controller.py": "server.packages.flightcontroller.position_controller:PositionControllerNode",
        "velocity_controller.py": "server.packages.flightcontroller.velocity_controller:VelocityControllerNode",
        "angle_controller.py": "server.packages.flightcontroller.angle_controller:AngleControllerNode",
    },
    "flightgoggles": {
        "flightgoggles_uav_dynamics": "server.packages.flightgoggles.uav_dynamics:UavDynamicsNode"
    },
    "simple_sim": {"simple_sim_node": "server.packages.simple_sim.simple_sim_node:SimpleSimNode"},
    "simple_control": {"keyboard_manager": "server.packages.simple_control.keyboard_manager:KeyboardManager"},
    "visualizer": {"gui_controller.py": "server.packages.visualizer.gui_controller:GUIControllerNode"},
    "sensor_simulation": {"pressure.py": "server.packages.sensor_simulation.pressure:PressureSensorNode"},
    "demo_nodes_py": {
        "talker": "server.packages.demo_nodes_py.talker:Talker",
        "listener": "server.packages.demo_nodes_py.listener:Listener",
    },
    "demo_nodes_cpp": {
        "talker": "server.packages.demo_nodes_cpp.talker:Talker",
        "listener": "server.packages.demo_nodes_py.listener:Listener",
    },
    "turtlesim": {
        "turtlesim_node": "server.packages.turtlesim.turtlesim_node:TurtlesimNode",
        "mimic": "server.packages.turtlesim.mimic:MimicNode",
    },
    "lab": {},
}


__all__ = [
    "BUILTIN",
    "Executable",
    "ExecutableNotFoundError",
    "NotInProcessError",
    "PackageIndex",
    "PackageNotFoundError",
    "WorkspaceError",
]


class PackageNotFoundError(LookupError):
    def __init__(self, pkg: str, known: list[str]) -> None:
        self.pkg = pkg
        super().__init__(f"package {pkg!r} not found (known: {', '.join(known)})")


class ExecutableNotFoundError(LookupError):
    def __init__(self, pkg: str, exe: str, known: list[str]) -> None:
        self.pkg, self.exe = pkg, exe
        super().__init__(f"package {pkg!r} has no executable {exe!r} (it has: {', '.join(known) or 'none'})")


@dataclass(frozen=True)
class Executable:
    """What ``(pkg, exec)`` names: a lab node (``module:Class``) or a student's file."""

    pkg: str
    name: str
    builtin: str | None = None  # "module:Class"
    file: Path | None = None  # a student's file (for a console script: its module's file)
    entry_point: EntryPoint | None = None  # a student's console script

    @property
    def target(self) -> Path | str | EntryPoint:
        """What a node process runs (server.host.processes.command.node_command)."""
        return self.entry_point or self.file or str(self.builtin)


class NotInProcessError(LookupError):
    """A student's file asked to run inside the app: it runs as its own process instead."""

    def __init__(self, exe: Executable) -> None:
        super().__init__(f"{exe.file}: a student's node runs as its own process, not inside the app")


@dataclass
class PackageIndex:
    """The packages a launch can name: the built-in ones, overlaid by a student workspace."""

    workspace: Path | None = None
    executables: dict[str, dict[str, str | Callable[[], Node]]] = field(
        default_factory=lambda: {pkg: dict(exes) for pkg, exes in BUILTIN.items()}
    )

    def student_workspace(self) -> Workspace:
        """The workspace's packages, found afresh (a student adds packages while the lab runs)."""
        return find_packages(self.workspace) if self.workspace is not None else Workspace()

    def interfaces(self, *, log_problems: bool = False) -> WorkspaceInterfaces | None:
        """The workspace's interface packages, read now and again whenever a type name is not known
        (node_runtime.ament.interfaces); None without a workspace."""
        if self.workspace is None:
            return None
        from node_runtime.ament.interfaces import workspace_interfaces  # the message types: see above

        return workspace_interfaces(self.workspace, log_problems=log_problems)

    def _student(self, pkg: str) -> WorkspacePackage | None:
        return self.student_workspace().get(pkg)  # WorkspaceError: a duplicate name, a bad package.xml

    def names(self) -> list[str]:
        return sorted(set(self.executables) | set(self.student_workspace().packages))

    def roots(self) -> tuple[Path, ...]:
        """The folders every package's files lie in: the lab's own packages and the workspace."""
        return (HERE,) if self.workspace is None else (HERE, self.workspace)

    def share_dir(self, pkg: str) -> Path:
        student = self._student(pkg)
        if student is not None and ((student.path / "launch").is_dir() or pkg not in self.executables):
            return student.path
        if pkg in self.executables:
            return HERE / pkg
        raise PackageNotFoundError(pkg, self.names())

    def executables_of(self, pkg: str) -> dict[str, Executable]:
        """A package's executables by name; a student's files win over the lab's of the same name."""
        exes = {
            name: Executable(pkg, name, builtin=t) if isinstance(t, str) else Executable(pkg, name)
            for name, t in self.executables.get(pkg, {}).items()
        }
        student = self._student(pkg)
        if student is not None:
            exes |= {
                name: Executable(pkg, name, file=exe.file, entry_point=exe.entry_point)
                for name, exe in student.executables().items()
            }
        elif pkg not in self.executables:
            raise PackageNotFoundError(pkg, self.names())
        return exes

    def resolve(self, pkg: str, exe: str) -> Executable:
        exes = self.executables_of(pkg)
        found = exes.get(exe)
        if found is None:
            raise ExecutableNotFoundError(pkg, exe, sorted(exes))
        return found

    def factory(self, pkg: str, exe: str) -> Callable[[], Node]:
        """The class of a lab node, to make it inside the app (NotInProcessError for a student's file)."""
        target = self.executables.get(pkg, {}).get(exe)
        found = self.resolve(pkg, exe)
        if found.file is not None:
            raise NotInProcessError(found)
        if callable(target):
            return target
        assert isinstance(target, str)
        module, _, attr = target.partition(":")
        factory: Callable[[], Node] = getattr(importlib.import_module(module), attr)
        return factory
