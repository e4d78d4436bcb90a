"""The running lab: bus, executor, devices, launched nodes and views, wired in one place.

``create_app`` owns one Lab for its lifetime; tests can build one with a ManualClock and no
display, and step it by hand.
"""

from __future__ import annotations

import asyncio
import dataclasses
import itertools
import logging
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from server.bag.manager import BagManager
from server.bus import (
    Bus,
    Clock,
    Executor,
    ExecutorGroup,
    Node,
    Publisher,
    SystemClock,
    TopicTypeError,
    UnknownTopicError,
    validate_node_name,
)
from server.devices.deadman import KeyDeadMan
from server.devices.keyboard import KeyboardDevice
from server.introspection.merged import topic_views
from server.launch.description import NodeAction, SourceLocation
from server.launch.launcher import LaunchedNode, Launcher, ProcessTransport
from server.limits import LimitExceededError, RateLimit, check_finite_json, check_topic_limits, per_second
from server.msgs import Message, get_service_type, get_type
from server.packages import PackageIndex
from server.publishers import PublisherManager
from server.service_calls import ServiceCaller
from server.settings import Settings
from server.topic_watch import TopicWatch
from server.transport.config import ZenohSettings
from server.transport.remote_graph import RemoteGraph

log = logging.getLogger("lab")
Trigger = get_service_type("std_srvs/srv/Trigger")

LAUNCH_ALIASES = {
    "rocket": ("rocketship", "rocket.launch"),
    "fly": ("flightcontroller", "fly.launch"),
    "all": ("lab", "all.launch"),
}


def resolve_launch(launch: str, packages: PackageIndex) -> Path:
    """``rocket``, ``fly``, ``all`` or a path → the launch file's path."""
    if launch in LAUNCH_ALIASES:
        pkg, file = LAUNCH_ALIASES[launch]
        return packages.share_dir(pkg) / "launch" / file
    return Path(launch)


RESET_SERVICE = "/rocket/reset"


class ApiNode(Node):
    """Hidden node ``_rest_api`` that owns the publishers REST calls use (like rqt's publisher),
    and serves the lab's own controls as ROS services (``/rocket/reset``)."""

    def __init__(self, max_topics: int, reset_rocket: Callable[[], bool]) -> None:
        super().__init__("_rest_api")
        self.max_topics = max_topics
        self.pubs: dict[str, Publisher] = {}
        self._reset_rocket = reset_rocket
        self.create_service(Trigger, RESET_SERVICE, self._on_reset)

    def _on_reset(self, request: Any, response: Any) -> Any:
        response.success = self._reset_rocket()
        response.message = "rocket back on the pad" if response.success else "no rocket in this launch"
        return response

    def publisher_for(self, topic: str, msg_type: type[Message]) -> Publisher:
        pub = self.pubs.get(topic)
        if pub is not None and pub.msg_type is msg_type:
            return pub
        if pub is None and len(self.pubs) >= self.max_topics:
            raise LimitExceededError("topics published by the API", self.max_topics)
        pub = self.create_publisher(msg_type, topic, 10)
        self.pubs[topic] = pub
        return pub


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


class Lab:
    def __init__(
        self, settings: Settings, clock: Clock | None = None, *, executors: ExecutorGroup | None = None
    ) -> None:
        self.settings = settings
        self.bus = Bus(clock or SystemClock())
        self.executor = Executor(self.bus)
        # A class server's worlds share one task that runs their executors; alone, the lab has its own.
        self.executors = executors
        self.packages = PackageIndex(workspace=settings.workspace)
        self.launcher = Launcher(self.bus, self.packages)
        self.launcher.all_processes = settings.node_processes == "all"
        self.keyboard = KeyboardDevice()
        self.bus.devices["keyboard"] = self.keyboard
        self.key_deadman = KeyDeadMan(self.keyboard, self.bus, settings.deadman_s)
        self.key_frames = RateLimit(self.bus.clock, settings.key_frames_hz, settings.key_frames_burst)
        self.socket_frames = per_second(self.bus.clock, settings.socket_frames_hz)
        self.socket_requests = per_second(self.bus.clock, settings.socket_requests_hz)
        self.display: Any = None
        self.rocket_view: Any = None
        self.started_at = time.monotonic()
        self._spin_task: asyncio.Task[None] | None = None
        self.zenoh: Any = None  # server.transport.link.ZenohLink while the graph is on Zenoh
        self.zenoh_error: str | None = None
        with self.bus.activate():
            self.api_node = ApiNode(settings.max_api_topics, self.reset_rocket)
        self.publishers = PublisherManager(self, settings.max_publishers)
        self.service_caller = ServiceCaller(self.api_node)
        self.topic_watch = TopicWatch(self.bus)
        self.bags = BagManager(self.bus, settings.bag_dir)  # ros2 bag record / play
        self.launch_groups: dict[str, LaunchGroup] = {}
        self._group_ids = itertools.count(1)
        self.stopped = asyncio.Event()  # set by stop(): open WebSockets close, and clients reconnect

    # -- life ----------------------------------------------------------------
    def launch_path(self, launch: str) -> Path:
        return resolve_launch(launch, self.packages)

    def start_nodes(self) -> None:
        """Launch the configured launch file and the tool nodes (views); no event loop needed."""
        self.launcher.launch_file(self.launch_path(self.settings.launch), self.settings.launch_args)
        if any(e.action.pkg == "rocketship" for e in self.launcher.launched):
            from server.viewer.rocket_view import RocketViewNode

            with self.bus.activate():
                self.rocket_view = RocketViewNode(self.display, self.reset_rocket)
        if self.display is not None:
            from server.viewer.publisher_panel import PageToolsNode

            self.page_tools = PageToolsNode(self)
            from server.viewer.record_panel import RecordPanel  # record a flight, download it

            self.record_panel = RecordPanel(self)

    async def start(self) -> None:
        if self.settings.zenoh is not None:
            from server.transport.link import open_link

            self.zenoh, self.zenoh_error = await open_link(self.bus, self._zenoh_settings())
            if self.zenoh is not None:
                zenoh = self.zenoh.settings
                self.launcher.transport = ProcessTransport(
                    self.zenoh.router_endpoint(), zenoh.domain_id, zenoh.login
                )
                remote = self.zenoh.bridge.remote
                self.launcher.on_process_start.append(
                    lambda p: remote.name_session(p.command.zid, f"process {p.pid}")
                )
        if self.settings.viewer:
            from server.viewer.display import Display

            self.display = Display(asyncio.get_running_loop())
            self.bus.devices["display"] = self.display
        self.start_nodes()
        if self.executors is not None:
            self.executors.add(self.executor)
        else:
            self._spin_task = asyncio.create_task(self.executor.spin(), name="executor")

    def _zenoh_settings(self) -> ZenohSettings:
        """The graph's session; a lab behind ``--token`` that is the router logs every session in (its
        node processes, and anyone given ``GET /api/zenoh/join``), as its HTTP port asks for the token."""
        zenoh = self.settings.zenoh
        assert zenoh is not None
        if zenoh.mode != "router" or self.settings.token is None or self.settings.classroom:
            return zenoh
        from server.transport.acl import ClassAuth, RouterAccess

        login = ClassAuth(self.settings.token).class_credentials()
        return dataclasses.replace(zenoh, router_logins=RouterAccess(login), login=login)

    async def stop(self) -> None:
        self.stopped.set()
        if self.executors is not None:
            self.executors.remove(self.executor)
        self.executor.stop()
        if self._spin_task is not None:
            await self._spin_task
        self.publishers.stop_all()
        self.bags.stop_all()
        self.launcher.shutdown()
        for node in list(self.bus.nodes):
            node.destroy_node()
        if self.zenoh is not None:
            self.zenoh.close()
            self.zenoh = None
        if self.display is not None:
            self.display.stop()

    def remote_graph(self) -> RemoteGraph | None:
        """Nodes and endpoints of other processes, while the graph is on Zenoh."""
        return self.zenoh.bridge.remote if self.zenoh is not None else None

    def died_nodes(self) -> list[dict[str, Any]]:
        """Node processes that ended and are not running again (yet), for the node list."""
        out = []
        for entry in self.launcher.launched:
            process = entry.process
            if process is None or process.state != "died":
                continue
            action = entry.action
            namespace = action.namespace or "/"
            remote = self.remote_graph()
            names = remote.names_seen(process.command.zid) if remote is not None else []
            fallback = namespace.rstrip("/") + "/" + (action.name or Path(action.exec).stem).split("/")[-1]
            for name in names or [fallback]:
                out.append({
                    "name": name, "namespace": name.rsplit("/", 1)[0] or "/", "state": "died",
                    "location": f"process {process.pid}", "exit_code": process.exit_code,
                    "respawn": None if entry.respawn is None else entry.respawn.describe(),
                })  # fmt: skip
        return out

    def topic_type(self, name: str, type_name: str | None) -> type[Message]:
        """The type ``name`` carries: ``type_name`` if given (it must agree with the graph), else the
        type this process or another process uses on it. UnknownTopicError if none does."""
        existing = self.bus.topics.get(name)
        if existing is not None:
            known = {existing.msg_type.TYPE}
        else:
            known = {v.type for v in topic_views(self.bus, self.remote_graph()) if v.name == name}
        if type_name is not None:
            msg_type = get_type(type_name)
            if existing is not None and existing.msg_type is not msg_type:
                raise TopicTypeError(f"{name} carries {existing.msg_type.TYPE}, not {msg_type.TYPE}")
            return msg_type
        if not known:
            raise UnknownTopicError(name)
        if len(known) > 1:
            raise TopicTypeError(f"{name} carries several types ({', '.join(sorted(known))}): name one")
        return get_type(known.pop())

    # -- actions -------------------------------------------------------------
    def prepare(self, topic: str, msg: dict[str, Any], type_name: str | None) -> tuple[str, Message]:
        """Resolve the topic and build the message from JSON, refusing what no node should get."""
        check_finite_json(msg)
        name = self.api_node.resolve_topic_name(topic)
        msg_type = self.topic_type(name, type_name)
        message = msg_type.from_dict(msg)
        check_topic_limits(name, message)
        return name, message

    def publish(self, topic: str, msg: dict[str, Any], type_name: str | None) -> tuple[str, str, int]:
        """Publish one message from JSON; returns (topic, type, subscriptions reached)."""
        name, message = self.prepare(topic, msg, type_name)
        pub = self.api_node.publisher_for(name, type(message))
        return name, message.TYPE, pub.publish(message)

    def launch_group(self, path: Path, args: dict[str, str]) -> LaunchGroup:
        """Launch a file into the running graph, as ``ros2 launch`` does; LaunchFileError if it is bad.
        Everything is checked before the first node starts."""
        self._check_group_limit()
        description = self.launcher.parse(path, args)
        if len(description.nodes) > self.settings.max_nodes_per_launch:
            raise LimitExceededError("nodes in one launch", self.settings.max_nodes_per_launch)
        return self._group("launch", str(path), self.launcher.launch(description))

    def run_node(
        self,
        pkg: str,
        exe: str,
        name: str | None = None,
        parameters: dict[str, Any] | None = None,
        remappings: dict[str, str] | None = None,
    ) -> LaunchGroup:
        """Start one node, as ``ros2 run PKG EXEC --ros-args ...`` does."""
        self._check_group_limit()
        if name is not None:
            validate_node_name(name)
        self.packages.resolve(pkg, exe)  # an unknown package or executable is an error, not a failed node
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
        entry = self.launcher.start(action)
        self.launcher.launched.append(entry)
        return self._group("run", f"{pkg} {exe}", [entry])

    def _check_group_limit(self) -> None:
        if len(self.launch_groups) >= self.settings.max_launch_groups:
            raise LimitExceededError("launches and runs", self.settings.max_launch_groups)

    def _group(self, kind: str, source: str, entries: list[LaunchedNode]) -> LaunchGroup:
        group = LaunchGroup(f"{kind}{next(self._group_ids)}", source, entries)
        self.launch_groups[group.id] = group
        return group

    def group(self, group_id: str) -> LaunchGroup:
        group = self.launch_groups.get(group_id)
        if group is None:
            raise UnknownLaunchError(group_id)
        return group

    def stop_group(self, group_id: str) -> LaunchGroup:
        group = self.launch_groups.pop(group_id, None)
        if group is None:
            raise UnknownLaunchError(group_id)
        self.launcher.stop_all(group.entries)
        return group

    def reset_rocket(self) -> bool:
        """Put the rocket back on the pad: restart the rocket launch's nodes, as a student would.
        Returns whether there was a rocket to reset."""
        restarted = self.launcher.restart(
            lambda e: Path(e.file).name == "rocket.launch" and e.action.pkg == "rocketship"
        )
        if self.rocket_view is not None:
            self.rocket_view.reset()
        log.info("rocket reset: back on the pad, countdown restarted")
        return bool(restarted)
