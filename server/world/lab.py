"""The running lab: bus, executor, devices, launched nodes and views, wired in one place.

``create_app`` owns one Lab for its lifetime; tests can build one with a ManualClock and no
display, and step it by hand.
"""

from __future__ import annotations

import asyncio
import dataclasses
import time
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

from node_runtime.ament.index import PackageIndex
from node_runtime.bus import (
    Bus,
    Clock,
    Executor,
    ExecutorGroup,
    SystemClock,
    TopicTypeError,
    UnknownTopicError,
)
from node_runtime.limits import RateLimit, check_finite_json, check_topic_limits, per_second
from node_runtime.msgs import Message, get_type
from node_runtime.transport.config import ZenohSettings
from node_runtime.transport.remote_graph import RemoteGraph
from server.host.introspection.merged import topic_views
from server.host.processes.sandbox import StudentCodeRefusedError, probe
from server.host.processes.start_pacing import StartPacer, default_slots
from server.host.settings import Settings
from server.packages.rocketship.controls import RocketControls
from server.peripherals.bag.manager import BagManager
from server.peripherals.devices.deadman import KeyDeadMan
from server.peripherals.devices.keyboard import KeyboardDevice
from server.services.api_node.publishers import PublisherManager
from server.services.api_node.rest_node import ApiNode
from server.services.api_node.service_calls import ServiceCaller
from server.services.api_node.topic_watch import TopicWatch
from server.services.launch.aliases import resolve_launch
from server.services.launch.commands import LabCli
from server.services.launch.groups import LaunchGroups, NodeBudget
from server.services.launch.launcher import Launcher, ProcessTransport
from server.world.checkpoints.catalog import load as load_checkpoints
from server.world.checkpoints.progress import Progress
from server.world.checkpoints.watcher import CheckpointWatch

if TYPE_CHECKING:
    from node_runtime.transport.link import ZenohLink
    from server.peripherals.viewer.display import Display
    from server.peripherals.viewer.publisher_panel import PageToolsNode
    from server.peripherals.viewer.record_panel import RecordPanel


class Lab:
    """One world, its parts built here. A class's world is given what the class's worlds share
    (``executors``, ``node_budget``, ``start_pacer``, the physics among ``devices``), its progress so
    far, its ``label`` (its name, on its nodes' console lines) and ``sandbox_unreachable``: what to
    say instead when a sandbox could be built here but cannot reach the graph's router (a world
    worker away from the class's router)."""

    def __init__(
        self,
        settings: Settings,
        clock: Clock | None = None,
        *,
        executors: ExecutorGroup | None = None,
        progress: Progress | None = None,
        node_budget: NodeBudget | None = None,
        start_pacer: StartPacer | None = None,
        label: str | None = None,
        devices: Mapping[str, Any] | None = None,
        sandbox_unreachable: StudentCodeRefusedError | None = None,
    ) -> None:
        self.settings = settings
        limits = settings.limits
        self.bus = Bus(clock or SystemClock())
        self.bus.label = label  # its nodes' console lines carry it (node_runtime/console.py)
        self.executor = Executor(self.bus)
        # A class server's worlds share one task that runs their executors; alone, the lab has its own.
        self.executors = executors
        self._sandbox_unreachable = sandbox_unreachable
        self.packages = PackageIndex(workspace=settings.lab.workspace)
        self.packages.interfaces(log_problems=True)  # a student's own .msg/.srv types, with no build
        # Node processes starting at once on this server's cores: a class server's worlds share
        # one pacer. ``ros2lab run`` asks it before it starts (GET /api/zenoh/join?start=true);
        # where the server serves others, the page's runs of students' files wait for it too.
        self.start_pacer = start_pacer or StartPacer(default_slots(), clock=self.bus.clock.now)
        cli = None
        if not settings.confines_paths:  # a launch file's ros2 commands: this lab's CLI, as its user
            host = settings.listen.host
            url = f"http://{f'[{host}]' if ':' in host else host}:{settings.listen.port}"
            cli = LabCli(url, settings.listen.token)
        self.launcher = Launcher(
            self.bus,
            self.packages,
            all_processes=settings.lab.node_processes == "all",
            confined=settings.confines_paths,
            cli=cli,
            start_pacer=self.start_pacer if settings.confines_paths else None,
        )
        self.keyboard = KeyboardDevice()
        self.bus.devices.update(devices or {})
        self.bus.devices["keyboard"] = self.keyboard
        self.key_deadman = KeyDeadMan(self.keyboard, self.bus, limits.deadman_s)
        self.key_frames = RateLimit(self.bus.clock, limits.key_frames_hz, limits.key_frames_burst)
        self.socket_frames = per_second(self.bus.clock, limits.socket_frames_hz)
        self.socket_requests = per_second(self.bus.clock, limits.socket_requests_hz)
        self.display: Display | None = None
        self.page_tools: PageToolsNode | None = None
        self.record_panel: RecordPanel | None = None
        self.started_at = time.monotonic()
        self._spin_task: asyncio.Task[None] | None = None
        self.zenoh: ZenohLink | None = None  # while the graph is on Zenoh
        self.zenoh_error: str | None = None
        self._socket: Path | None = None  # the Unix socket its own router opened for sandboxed nodes
        self.rocket = RocketControls(self.launcher)
        with self.bus.activate():
            self.api_node = ApiNode(limits.max_api_topics)
        self.rocket.serve(self.api_node)
        self.publishers = PublisherManager(self, limits.max_publishers)
        self.service_caller = ServiceCaller(self.api_node)
        self.topic_watch = TopicWatch(self.bus)
        self.bags = BagManager(self.bus, settings.lab.bag_dir)  # ros2 bag record / play
        # A class server's worlds share one budget of node processes; alone, the lab has its own.
        self.launch_groups = LaunchGroups(
            self.launcher,
            self.packages,
            limits.max_launch_groups,
            limits.max_nodes_per_launch,
            limits.max_running_nodes,
            node_budget or NodeBudget(limits.max_server_nodes),
        )
        # The checkpoints: ``progress`` is the world's so far (kept across a reset), else a new one.
        progress = progress or Progress(load_checkpoints(settings.lab.checkpoints))
        self.checkpoints = CheckpointWatch(
            self.bus, self.launcher, self.packages, progress, self.remote_graph
        )
        self.stopped = asyncio.Event()  # set by stop(): open WebSockets close, and clients reconnect

    # -- life ----------------------------------------------------------------
    def launch_path(self, launch: str) -> Path:
        return resolve_launch(launch, self.packages)

    def start_nodes(self) -> None:
        """Launch the configured launch file and the tool nodes (views); no event loop needed."""
        self.launcher.launch_file(self.launch_path(self.settings.lab.launch), self.settings.lab.launch_args)
        self.rocket.start_view(self.bus, self.display, self.launcher.launched)
        if self.display is not None:
            from server.peripherals.viewer.publisher_panel import PageToolsNode
            from server.peripherals.viewer.record_panel import RecordPanel

            self.page_tools = PageToolsNode(self)
            self.record_panel = RecordPanel(self)

    async def start(self) -> None:
        if self.settings.lab.zenoh is not None:
            from node_runtime.transport.link import open_link

            self.zenoh, self.zenoh_error = await open_link(self.bus, self._zenoh_settings())
            from server.services.launch.student_code import for_lab

            socket = self.zenoh.settings.process_socket if self.zenoh is not None else None
            sandbox = for_lab(self.settings, socket)
            refused = isinstance(sandbox, StudentCodeRefusedError)
            # A sandbox could be built here, and it is the router that is out of its reach: say so.
            if refused and self._sandbox_unreachable is not None and probe() is None:
                sandbox = self._sandbox_unreachable
            if self.zenoh is None:
                self.launcher.use_graph(None, sandbox)
            else:
                zenoh = self.zenoh.settings
                remote = self.zenoh.bridge.remote
                self.launcher.use_graph(
                    ProcessTransport(self.zenoh.router_endpoint(), zenoh.domain_id, zenoh.login),
                    sandbox,
                    lambda p: remote.name_session(p.command.zid, f"process {p.pid}"),
                )
        if self.settings.lab.viewer:
            from server.peripherals.viewer.display import Display

            self.display = Display(asyncio.get_running_loop())
            self.bus.devices["display"] = self.display
        started = time.perf_counter()
        self.checkpoints.start()  # first: it sees the lab's own launch
        self.start_nodes()
        if self.executors is not None:  # a class world's start (a join, a reset) is charged to it
            self.executors.add(self.executor, charge_s=time.perf_counter() - started)
        else:
            self._spin_task = asyncio.create_task(self.executor.spin(), name="executor")

    def _zenoh_settings(self) -> ZenohSettings:
        """The graph's session; a lab behind ``--token`` that is the router logs every session in (its
        node processes, and anyone given ``GET /api/zenoh/join``), as its HTTP port asks for the token."""
        zenoh = self.settings.lab.zenoh
        assert zenoh is not None
        token = self.settings.listen.token
        if zenoh.mode != "router" or token is None or self.settings.classroom is not None:
            return zenoh
        from node_runtime.transport.acl import ClassAuth, RouterAccess

        login = ClassAuth(token).class_credentials()
        zenoh = dataclasses.replace(zenoh, router_logins=RouterAccess(login), login=login)
        if self.settings.sandboxes_students:  # its sandboxed nodes reach the router on a Unix socket
            from node_runtime.transport.router_socket import new_socket_path, socket_endpoint

            self._socket = new_socket_path()
            zenoh = dataclasses.replace(
                zenoh, listen=(*zenoh.listen, socket_endpoint(self._socket)), process_socket=self._socket
            )
        return zenoh

    async def stop(self) -> None:
        self.stopped.set()
        if self.executors is not None:
            self.executors.remove(self.executor)
        self.executor.stop()
        if self._spin_task is not None:
            await self._spin_task
        self.checkpoints.stop()
        self.publishers.stop_all()
        self.bags.stop_all()
        self.launcher.shutdown()
        for node in list(self.bus.nodes):
            node.destroy_node()
        if self.zenoh is not None:
            self.zenoh.close()
            self.zenoh = None
        if self._socket is not None:
            from node_runtime.transport.router_socket import remove

            remove(self._socket)
            self._socket = None
        if self.display is not None:
            self.display.stop()

    def remote_graph(self) -> RemoteGraph | None:
        """Nodes and endpoints of other processes, while the graph is on Zenoh."""
        return self.zenoh.bridge.remote if self.zenoh is not None else None

    def joined_names(self, zid: str) -> list[str]:
        """The nodes a node process's session (``zid``) has declared in the graph, even if gone
        since; none while it is starting, or where the graph is not on Zenoh."""
        remote = self.remote_graph()
        return remote.names_seen(zid) if remote is not None else []

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
