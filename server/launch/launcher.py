"""The launcher: starts the nodes a LaunchDescription names, restarts them, respawns crashed ones."""

from __future__ import annotations

import logging
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path

from server.bus import Bus, Node, NodeOverrides
from server.bus.faults import is_node_fault
from server.packages import PackageIndex

from .description import LaunchDescription, NodeAction
from .respawn import RespawnBackoff, RespawnPolicy
from .xml_parser import parse_launch_file

log = logging.getLogger("launch")


def parse_launch(
    path: str | Path, args: Mapping[str, str] | None, packages: PackageIndex
) -> LaunchDescription:
    """Read a launch file, resolving ``$(find-pkg-share PKG)`` through ``packages``."""
    return parse_launch_file(Path(path), args=dict(args or {}), find_package_share=packages.share_dir)


@dataclass
class LaunchedNode:
    """A node the launcher started (or failed to start) from one ``<node>`` action."""

    action: NodeAction
    node: Node | None = None
    error: str | None = None
    starts: int = 0
    respawn: RespawnBackoff | None = None  # only for respawn="true"

    @property
    def file(self) -> str:
        return self.action.location.file


class Launcher:
    def __init__(self, bus: Bus, packages: PackageIndex, respawn_policy: RespawnPolicy | None = None) -> None:
        self.bus = bus
        self.packages = packages
        self.respawn_policy = respawn_policy or RespawnPolicy()
        self.launched: list[LaunchedNode] = []
        self._respawner: Node | None = None
        bus.crash_handlers.append(self._on_crash)

    def parse(self, path: str | Path, args: Mapping[str, str] | None = None) -> LaunchDescription:
        return parse_launch(path, args, self.packages)

    def launch_file(self, path: str | Path, args: Mapping[str, str] | None = None) -> list[LaunchedNode]:
        return self.launch(self.parse(path, args))

    def launch(self, description: LaunchDescription) -> list[LaunchedNode]:
        started = [self.start(action) for action in description.nodes]
        self.launched.extend(started)
        return started

    def start(self, action: NodeAction, entry: LaunchedNode | None = None) -> LaunchedNode:
        """Construct the node; a failure is recorded and logged, and the rest of the graph runs on."""
        entry = entry or LaunchedNode(action)
        entry.starts += 1
        overrides = NodeOverrides(
            name=action.name, namespace=action.namespace,
            parameters=dict(action.parameters), remappings=dict(action.remappings),
        )  # fmt: skip
        before = list(self.bus.nodes)
        try:
            factory = self.packages.factory(action.pkg, action.exec)
            with self.bus.activate(overrides):
                node = factory()
            if not isinstance(node, Node):
                raise TypeError(f"{action.pkg}/{action.exec} made a {type(node).__name__}, not a Node")
        except BaseException as exc:  # SystemExit from a constructor included
            if not is_node_fault(exc):
                raise
            for orphan in [n for n in self.bus.nodes if n not in before]:
                orphan.destroy_node()  # half-built: drop what its constructor registered
            entry.node, entry.error = None, f"{type(exc).__name__}: {exc}"
            log.error(
                "%s: node %s (%s %s) failed to start: %s",
                action.location,
                action.name or action.exec,
                action.pkg,
                action.exec,
                entry.error,
            )
            return entry
        node.origin = {"package": action.pkg, "executable": action.exec, "launch_file": str(action.location)}
        entry.node, entry.error = node, None
        if action.respawn:
            entry.respawn = entry.respawn or RespawnBackoff(self.respawn_policy, self.bus.clock)
            entry.respawn.started()
        return entry

    def respawn_of(self, node: Node) -> RespawnBackoff | None:
        """The respawn state of a launched node, for the node list."""
        return next((e.respawn for e in self.launched if e.node is node), None)

    def stop(self, entry: LaunchedNode) -> None:
        if entry.node is not None:
            entry.node.destroy_node()
            entry.node = None

    def stop_all(self, entries: list[LaunchedNode]) -> None:
        """Stop these nodes and forget them (a launch ended with Ctrl-C)."""
        for entry in reversed(entries):
            self.stop(entry)
        self.launched = [e for e in self.launched if e not in entries]

    def restart(self, predicate: Callable[[LaunchedNode], bool]) -> list[LaunchedNode]:
        """Stop and start again every launched node that ``predicate`` picks, in launch order."""
        chosen = [e for e in self.launched if predicate(e)]
        for entry in reversed(chosen):
            self.stop(entry)
        for entry in chosen:
            self.start(entry.action, entry)
        return chosen

    def shutdown(self) -> None:
        for entry in reversed(self.launched):
            self.stop(entry)
        self.launched.clear()
        if self._respawner is not None:
            self._respawner.destroy_node()
            self._respawner = None

    def _on_crash(self, node: Node, exc: BaseException) -> None:
        entry = next((e for e in self.launched if e.node is node), None)
        if entry is None or not entry.action.respawn:
            return
        if entry.respawn is None:
            entry.respawn = RespawnBackoff(self.respawn_policy, self.bus.clock)
        delay = entry.respawn.crashed(entry.action.respawn_delay_s)
        if delay is None:
            log.error("%s crashed %d times soon after starting; no more respawns", node.fully_qualified_name,
                      entry.respawn.fast_failures - 1)  # fmt: skip
            return
        if self._respawner is None:
            with self.bus.activate():
                self._respawner = Node("_launch_respawner")
        log.warning("%s crashed; respawning in %.2f s", node.fully_qualified_name, delay)

        def respawn() -> None:
            timer.cancel()
            self.stop(entry)
            self.start(entry.action, entry)

        timer = self._respawner.create_timer(delay, respawn)
