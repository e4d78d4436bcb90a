"""Watching one world for its checkpoints, at little cost and never in the sim loop's way.

Taps on the few topics the checks read (Bus.set_tap) put each message, with its publisher, in a
bounded queue: one append, and GPS thinned to GPS_EVERY_S first. A hidden node's timer drains the
queue every DRAIN_S, turns the messages into events (events.py) and feeds every check; what a
check meets goes to the world's Progress, which outlives this watch (a reset makes a new one).
"""

from __future__ import annotations

import logging
from collections import deque
from collections.abc import Callable
from dataclasses import asdict
from pathlib import Path
from typing import Any

from node_runtime.ament.index import PackageIndex
from node_runtime.bus import Bus, Node
from node_runtime.msgs import Message
from node_runtime.transport.remote_graph import RemoteGraph
from server.host.introspection.graph import graph_snapshot
from server.services.launch.description import LaunchDescription
from server.services.launch.launcher import LaunchedNode, Launcher
from server.world.checkpoints import events as ev
from server.world.checkpoints.declared import Check, Evidence
from server.world.checkpoints.progress import Progress
from server.world.checkpoints.sources import Sources

log = logging.getLogger("checkpoints")
DRAIN_S = 0.2
GPS_EVERY_S = 0.05
MAX_QUEUED = 4096
GPS = "/uav/sensors/gps"
TOPICS = ("/keydown", "/abort_takeoff", "/cmd_vel", "/countdown", "/uav/input/position", GPS)


def _event(t_s: float, topic: str, msg: Any, source: ev.Source) -> ev.Event | None:
    """The event a message on ``topic`` is, or None when it has not the lab's type."""
    try:
        if topic == GPS:
            p = msg.pose.position
            return ev.Gps(t_s, (float(p.x), float(p.y), float(p.z)))
        if topic == "/uav/input/position":
            return ev.Setpoint(t_s, (float(msg.x), float(msg.y), float(msg.z)), source)
        if topic == "/keydown":
            return ev.KeyDown(t_s, int(msg.code), source)
        if topic == "/abort_takeoff":
            return ev.Abort(t_s, bool(msg.data), source)
        if topic == "/cmd_vel":
            return ev.CmdVel(t_s, float(msg.data))
        if topic == "/countdown":
            return ev.Countdown(t_s, int(msg.data), source)
    except (AttributeError, TypeError, ValueError):
        return None
    return None


def launch_label(path: Path, packages: PackageIndex) -> str:
    """How the Guide names a launch file: by its path in the student's workspace, or by its name
    and package; never by a path of the server's own machine (a student has no use for it)."""
    resolved = path.resolve()
    workspace = packages.workspace
    if workspace is not None and resolved.is_relative_to(workspace.resolve()):
        return resolved.relative_to(workspace.resolve()).as_posix()
    for pkg in packages.names():
        try:
            share = packages.share_dir(pkg).resolve()
        except (LookupError, OSError):
            continue
        if resolved.is_relative_to(share):
            return f"{path.name} of the package {pkg}"
    return path.name


class CheckpointWatch:
    def __init__(
        self,
        bus: Bus,
        launcher: Launcher,
        packages: PackageIndex,
        progress: Progress,
        remote: Callable[[], RemoteGraph | None] = lambda: None,
    ) -> None:
        self.bus = bus
        self.progress = progress
        self._launcher = launcher
        self._packages = packages
        self._remote = remote
        self.sources = Sources(launcher, packages, remote)
        self.checks: dict[str, Check] = {c.name: c.check() for c in progress.checkpoints}
        self._queue: deque[tuple[float, str, Message, object]] = deque(maxlen=MAX_QUEUED)
        self._gps_s = -1e18
        self.dropped = 0
        self.live_version = 0
        self._lines: dict[str, tuple[bool, str]] = {}
        self._watched = frozenset(n for c in progress.checkpoints for s in c.steps for n in s.running)
        self._running: frozenset[str] = frozenset()
        self._node: Node | None = None

    # -- life ----------------------------------------------------------------------------------
    def start(self) -> None:
        for topic in TOPICS:
            self.bus.set_tap(topic, self._tapper(topic))
        self._launcher.on_launch.append(self._on_launch)
        with self.bus.activate():
            self._node = Node("_checkpoints")
        self._node.create_timer(DRAIN_S, self.drain)

    def stop(self) -> None:
        for topic in TOPICS:
            self.bus.set_tap(topic, None)
        if self._on_launch in self._launcher.on_launch:
            self._launcher.on_launch.remove(self._on_launch)
        if self._node is not None:
            self._node.destroy_node()
            self._node = None

    # -- the sim loop's side: one append --------------------------------------------------------
    def _tapper(self, topic: str) -> Callable[[Message, object], None]:
        queue, clock = self._queue, self.bus.clock

        def tap(msg: Message, source: object) -> None:
            now = clock.now()
            if topic == GPS:
                if now - self._gps_s < GPS_EVERY_S:
                    return
                self._gps_s = now
            if len(queue) == MAX_QUEUED:
                self.dropped += 1
            queue.append((now, topic, msg, source))

        return tap

    def _on_launch(self, description: LaunchDescription, started: list[LaunchedNode]) -> None:
        if not description.files:
            return
        top = Path(description.files[0])
        workspace = self._packages.workspace
        in_workspace = workspace is not None and top.resolve().is_relative_to(workspace.resolve())
        label = launch_label(top, self._packages)
        try:
            text = top.read_text(errors="replace")[: ev.MAX_LAUNCH_TEXT]
        except OSError:
            text = ""
        nodes = tuple(
            ev.LaunchedNode(
                e.action.pkg,
                e.action.exec,
                e.action.name,
                self.sources.student_executable(e.action.pkg, e.action.exec),
            )
            for e in started
        )
        self.feed(ev.Launch(self.bus.clock.now(), label, text, in_workspace, nodes))

    # -- the checks' side ----------------------------------------------------------------------
    def drain(self) -> None:
        queue = self._queue
        while queue:
            t_s, topic, msg, source = queue.popleft()
            event = _event(t_s, topic, msg, self.sources.of(source) if topic != GPS else ev.UNKNOWN)
            if event is not None:
                self.feed(event)
        now = self.bus.clock.now()
        for name, check in self.checks.items():
            self._met(name, check.tick(now))

    def feed(self, event: ev.Event) -> None:
        for name, check in self.checks.items():
            self._met(name, check.feed(event))

    def _met(self, name: str, evidence: Evidence | None) -> None:
        if evidence is None:
            return
        if self.progress.checkpoint(name).wants_graph:
            evidence = {**evidence, "graph": self.graph()}
        self.progress.met(name, evidence)
        log.info("%s", self.bus.tagged(f"checkpoint {name} met"))

    def graph(self) -> dict[str, Any]:
        return asdict(graph_snapshot(self.bus, False, self._remote()))

    def lines(self) -> dict[str, tuple[bool, str]]:
        """Each check's (started, progress line) now; ``live_version`` moves when one changes."""
        now = self.bus.clock.now()
        lines = {name: (check.started, check.progress(now)) for name, check in self.checks.items()}
        if lines != self._lines:
            self._lines = lines
            self.live_version += 1
        return lines

    def running(self) -> frozenset[str]:
        """Which nodes the steps watch (Step.running) run now; ``live_version`` moves when that
        changes, as for the lines."""
        running = frozenset(n.fully_qualified_name for n in self.bus.nodes) & self._watched
        if running != self._running:
            self._running = running
            self.live_version += 1
        return running

    @property
    def version(self) -> int:
        return self.progress.version + self.live_version
