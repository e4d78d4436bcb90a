"""Launches and runs started through the API, each a group of nodes started and stopped together
(``ros2 launch`` and ``ros2 run`` against a running lab), with their limits."""

from __future__ import annotations

import itertools
from collections.abc import Iterator, ValuesView
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from server.bus import validate_node_name
from server.limits import LimitExceededError
from server.packages import PackageIndex

from .description import NodeAction, SourceLocation
from .launcher import LaunchedNode, Launcher


class UnknownLaunchError(LookupError):
    def __init__(self, group_id: str) -> None:
        super().__init__(f"no launch or run with id {group_id!r}")


@dataclass
class LaunchGroup:
    """Nodes started together by one launch or run request, stopped together."""

    id: str
    source: str
    entries: list[LaunchedNode]

    def describe(self) -> dict[str, Any]:
        return {
            "id": self.id,
            "file": self.source,
            "nodes": [
                {
                    "name": e.node.fully_qualified_name if e.node else (e.action.name or e.action.exec),
                    "pkg": e.action.pkg,
                    "exec": e.action.exec,
                    "error": e.error,
                    # a node here: active, crashed or destroyed; a node process: running, died or stopped
                    "state": e.node.state if e.node is not None else e.process.state if e.process else None,
                    "exit_code": e.process.exit_code if e.process is not None else None,
                    "process": e.process.label if e.process is not None else None,  # ros2 launch's label
                }
                for e in self.entries
            ],
        }

    def output(self) -> dict[str, Any]:
        """The group, and each node process's last lines with how many it printed in all."""
        processes = []
        for e in self.entries:
            if e.process is not None:
                lines, printed = e.process.output()
                processes.append({"label": e.process.label, "lines": lines, "printed": printed})
        return {"group": self.describe(), "processes": processes}


class LaunchGroups:
    """The groups running in one lab, by id (``launch1``, ``run2``): at most ``max_groups`` at once,
    and at most ``max_nodes`` nodes in one launch."""

    def __init__(self, launcher: Launcher, packages: PackageIndex, max_groups: int, max_nodes: int) -> None:
        self._launcher = launcher
        self._packages = packages
        self.max_groups = max_groups
        self.max_nodes = max_nodes
        self._groups: dict[str, LaunchGroup] = {}
        self._ids = itertools.count(1)

    def __len__(self) -> int:
        return len(self._groups)

    def __iter__(self) -> Iterator[str]:
        return iter(self._groups)

    def values(self) -> ValuesView[LaunchGroup]:
        return self._groups.values()

    def launch(self, path: Path, args: dict[str, str]) -> LaunchGroup:
        """Launch a file into the running graph, as ``ros2 launch`` does; LaunchFileError if it is bad.
        Everything is checked before the first node starts."""
        self._check_room()
        description = self._launcher.parse(path, args)
        if len(description.nodes) > self.max_nodes:
            raise LimitExceededError("nodes in one launch", self.max_nodes)
        return self._add("launch", str(path), self._launcher.launch(description))

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
        self._launcher.check_student_code(self._packages.resolve(pkg, exe))
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
        entry = self._launcher.start(action)
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
        return group

    def _check_room(self) -> None:
        if len(self._groups) >= self.max_groups:
            raise LimitExceededError("launches and runs", self.max_groups)

    def _add(self, kind: str, source: str, entries: list[LaunchedNode]) -> LaunchGroup:
        group = LaunchGroup(f"{kind}{next(self._ids)}", source, entries)
        self._groups[group.id] = group
        return group
