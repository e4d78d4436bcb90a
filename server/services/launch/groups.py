"""Launches and runs started through the API, each a group of nodes started and stopped together
(``ros2 launch`` and ``ros2 run`` against a running lab), with their limits: groups at once,
nodes in one launch, and node processes running at once, in the lab and in every lab of the
process together (``NodeBudget``: a class server's worlds share one)."""

from __future__ import annotations

import itertools
import weakref
from collections.abc import Iterator, ValuesView
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from node_runtime.ament.index import PackageIndex
from node_runtime.bus import validate_node_name
from node_runtime.limits import LimitExceededError
from server.services.launch.commands import LaunchedCommand
from server.services.launch.description import LaunchDescription, NodeAction, SourceLocation
from server.services.launch.launcher import LaunchedNode, Launcher


class UnknownLaunchError(LookupError):
    def __init__(self, group_id: str) -> None:
        super().__init__(f"no launch or run with id {group_id!r}")


@dataclass
class LaunchGroup:
    """Nodes started together by one launch or run request, stopped together."""

    id: str
    source: str
    entries: list[LaunchedNode]
    messages: list[str] = field(default_factory=list)  # a Python launch file's LogInfo lines, its prints
    commands: list[LaunchedCommand] = field(default_factory=list)  # its ros2 commands (ExecuteProcess)

    def describe(self) -> dict[str, Any]:
        return {
            "id": self.id,
            "file": self.source,
            "messages": self.messages,
            "nodes": [
                {
                    "name": e.node.fully_qualified_name if e.node else (e.action.name or e.action.exec),
                    "pkg": e.action.pkg,
                    "exec": e.action.exec,
                    "error": e.error,
                    # a node here: active, crashed or destroyed; a node process: waiting, running, died or stopped
                    "state": e.node.state if e.node is not None else e.process.state if e.process else None,
                    "exit_code": e.process.exit_code if e.process is not None else None,
                    "process": e.process.label if e.process is not None else None,  # ros2 launch's label
                }
                for e in self.entries
            ],
        }

    def output(self) -> dict[str, Any]:
        """The group, and each node or command process's last lines with how many it printed in all."""
        processes = []
        for process in [*(e.process for e in self.entries), *(c.process for c in self.commands)]:
            if process is not None:
                lines, printed = process.output()
                processes.append({"label": process.label, "lines": lines, "printed": printed})
        return {"group": self.describe(), "processes": processes}

    def running_processes(self) -> int:
        """Its node processes that have not ended (those waiting for their turn to start too)."""
        return sum(
            1
            for e in self.entries
            if e.process is not None
            and e.process.exit_code is None
            and e.process.state in ("running", "waiting")
        )


class NodeBudget:
    """How many node processes the API's launches and runs of every lab in this process may keep
    running together."""

    def __init__(self, limit: int) -> None:
        self.limit = limit
        self._labs: weakref.WeakSet[LaunchGroups] = weakref.WeakSet()

    def join(self, groups: LaunchGroups) -> None:
        self._labs.add(groups)

    def running(self) -> int:
        return sum(groups.running_processes() for groups in list(self._labs))


class LaunchGroups:
    """The groups running in one lab, by id (``launch1``, ``run2``): at most ``max_groups`` at once,
    at most ``max_nodes`` nodes in one launch, at most ``max_running`` node processes running at
    once here, and no more than ``budget`` leaves for the whole process."""

    def __init__(
        self,
        launcher: Launcher,
        packages: PackageIndex,
        max_groups: int,
        max_nodes: int,
        max_running: int | None = None,
        budget: NodeBudget | None = None,
    ) -> None:
        self._launcher = launcher
        self._packages = packages
        self.max_groups = max_groups
        self.max_nodes = max_nodes
        self.max_running = max_running
        self.budget = budget
        if budget is not None:
            budget.join(self)
        self._groups: dict[str, LaunchGroup] = {}
        self._ids = itertools.count(1)

    def __len__(self) -> int:
        return len(self._groups)

    def __iter__(self) -> Iterator[str]:
        return iter(self._groups)

    def values(self) -> ValuesView[LaunchGroup]:
        return self._groups.values()

    def launch(
        self, path: Path, args: dict[str, str], description: LaunchDescription | None = None
    ) -> LaunchGroup:
        """Launch a file into the running graph, as ``ros2 launch`` does; LaunchFileError if it is bad.
        Everything is checked before the first node starts. ``description``: the file already read
        (``Launcher.parse``, which a caller may run off the loop: a Python file takes a process)."""
        self._check_room()
        description = description or self._launcher.parse(path, args)
        if len(description.nodes) + len(description.commands) > self.max_nodes:
            raise LimitExceededError("nodes in one launch", self.max_nodes)
        self._check_processes(self._processes_in(description))
        nodes, commands, refused = self._launcher.launch_all(description)
        group = self._add("launch", str(path), nodes)
        group.messages, group.commands = [*description.messages, *refused], commands
        return group

    def run(
        self,
        pkg: str,
        exe: str,
        name: str | None = None,
        parameters: dict[str, Any] | None = None,
        remappings: dict[str, str] | None = None,
    ) -> LaunchGroup:
        """Start one node, as ``ros2 run PKG EXEC --ros-args ...`` does."""
        self._check_room()
        if name is not None:
            validate_node_name(name)
        # An unknown package or executable is an error, not a failed node; so is a student's file
        # that this server does not run (StudentCodeRefusedError).
        resolved = self._packages.resolve(pkg, exe)
        self._launcher.check_student_code(resolved)
        self._check_processes(1 if self._launcher.runs_as_process(resolved) else 0)
        action = NodeAction(
            pkg=pkg,
            exec=exe,
            name=name,
            namespace=None,
            output="screen",
            respawn=False,
            respawn_delay_s=0.0,
            parameters=tuple((parameters or {}).items()),
            remappings=tuple((remappings or {}).items()),
            location=SourceLocation(f"<run {pkg} {exe}>", 0),
        )
        entry = self._launcher.start(action, exe=resolved)
        self._launcher.launched.append(entry)
        return self._add("run", f"{pkg} {exe}", [entry])

    def get(self, group_id: str) -> LaunchGroup:
        group = self._groups.get(group_id)
        if group is None:
            raise UnknownLaunchError(group_id)
        return group

    def stop(self, group_id: str) -> LaunchGroup:
        group = self._groups.pop(group_id, None)
        if group is None:
            raise UnknownLaunchError(group_id)
        self._launcher.stop_all(group.entries)
        self._launcher.commands.stop(group.commands)
        return group

    def _check_room(self) -> None:
        if len(self._groups) >= self.max_groups:
            raise LimitExceededError("launches and runs", self.max_groups)

    def running_processes(self) -> int:
        return sum(group.running_processes() for group in self._groups.values())

    def _processes_in(self, description: LaunchDescription) -> int:
        """How many of a launch's nodes would run as processes (one that cannot start counts none)."""
        count = 0
        for action in description.nodes:
            try:
                count += self._launcher.runs_as_process(self._packages.resolve(action.pkg, action.exec))
            except LookupError:
                continue
        return count

    def _check_processes(self, adding: int) -> None:
        """LimitExceededError (429) when ``adding`` more node processes would be too many."""
        if not adding:
            return
        if self.max_running is not None and self.running_processes() + adding > self.max_running:
            raise LimitExceededError(
                f"running node processes in this world ({self.running_processes()} run now, this starts {adding})",
                self.max_running,
            )
        if self.budget is not None and self.budget.running() + adding > self.budget.limit:
            raise LimitExceededError(
                f"running node processes on this server ({self.budget.running()} run now, this starts {adding})",
                self.budget.limit,
            )

    def _add(self, kind: str, source: str, entries: list[LaunchedNode]) -> LaunchGroup:
        group = LaunchGroup(f"{kind}{next(self._ids)}", source, entries)
        self._groups[group.id] = group
        return group
