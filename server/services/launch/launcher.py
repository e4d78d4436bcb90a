"""The launcher: starts the nodes (and commands) a LaunchDescription names, restarts them, respawns crashed ones."""

from __future__ import annotations

import contextlib
import logging
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path

from node_runtime.ament.index import Executable, PackageIndex
from node_runtime.bus import Bus, Node, NodeOverrides
from node_runtime.bus.faults import is_node_fault
from node_runtime.bus.parameter_service import serve_parameters
from node_runtime.transport.acl import Credentials
from server.host.processes.command import node_command, ros_args
from server.host.processes.sandbox import INSIDE_ROUTER, Sandbox, StudentCodeRefusedError
from server.host.processes.start_pacing import NEW_TURN, StartPacer, Turn
from server.host.processes.supervisor import ProcessNode, Supervisor
from server.services.launch.commands import CommandRunner, LabCli, LaunchedCommand
from server.services.launch.description import LaunchDescription, NodeAction
from server.services.launch.python_launch import RunPython
from server.services.launch.python_process import PythonLaunchProcess
from server.services.launch.respawn import RespawnBackoff, RespawnPolicy
from server.services.launch.xml_parser import parse_launch_file

log = logging.getLogger("launch")
# Lab nodes that drive a device of the app (the page's keys, the 3D view) stay in its process.
DEVICE_NODES = frozenset({("keyboard", "keyboard"), ("visualizer", "gui_controller.py")})
SCREEN_OUTPUTS = (None, "screen", "both", "full")


class NoGraphError(RuntimeError):
    """A node that must run as its own process, with the graph kept inside the app (no Zenoh)."""

    def __init__(self, what: str) -> None:
        super().__init__(
            f"{what} runs as its own process and joins the graph over Zenoh, which is off in this app "
            "(started with --no-zenoh, or its port was taken: see the first lines the app printed)"
        )


@dataclass(frozen=True)
class ProcessTransport:
    """Where node processes find the graph: the app's Zenoh router, and the ROS domain."""

    router: str
    domain_id: int = 0
    login: Credentials | None = None  # the user and password the router asks for (a class's)


def parse_launch(
    path: str | Path,
    args: Mapping[str, str] | None,
    packages: PackageIndex,
    *,
    confined: bool = False,
    run_python: RunPython | None = None,
) -> LaunchDescription:
    """Read a launch file, resolving ``$(find-pkg-share PKG)`` through ``packages``. A confined
    launch (a lab that serves others) includes only files of the world's packages, and
    ``$(env NAME)`` sees no variable of the server's environment (a default given still applies).
    A Python launch file is evaluated by ``run_python`` (by default in a process of its own, as
    the server's user)."""
    run_python = run_python or PythonLaunchProcess(packages.workspace, confined=confined)
    if not confined:
        return parse_launch_file(
            Path(path), args=dict(args or {}), find_package_share=packages.share_dir, run_python=run_python
        )
    return parse_launch_file(
        Path(path),
        args=dict(args or {}),
        find_package_share=packages.share_dir,
        environ={},
        roots=packages.roots(),
        run_python=run_python,
    )


def with_ros_arguments(lab_args: list[str], ros_arguments: tuple[str, ...]) -> list[str]:
    """The lab's ``--ros-args ...`` with a Python launch file's ``ros_arguments`` after them."""
    if not ros_arguments:
        return lab_args
    return [*(lab_args or ["--ros-args"]), *ros_arguments]


@dataclass
class LaunchedNode:
    """A node the launcher started (or failed to start) from one ``<node>`` action."""

    action: NodeAction
    node: Node | None = None
    error: str | None = None
    starts: int = 0
    respawn: RespawnBackoff | None = None  # only for respawn="true"
    process: ProcessNode | None = None  # a node that runs as its own process

    @property
    def file(self) -> str:
        return self.action.location.file

    def process_label(self) -> str:
        return self.process.label if self.process is not None else self.action.exec


class Launcher:
    """Starts a lab's launches. ``all_processes``: every lab node in its own process too (but the
    device nodes); ``confined``: includes and ``$(env)`` kept to the world's own packages
    (``parse_launch``); ``cli``: the CLI a launch file's ros2 commands run as (None: none run);
    ``start_pacer``: students' node processes start at their turn (a class: sixty "Run"s at once
    must not take the worlds' cores; None: at once). Where node processes find the graph, and how
    students' files run, come once the lab's graph is up (``use_graph``)."""

    def __init__(
        self,
        bus: Bus,
        packages: PackageIndex,
        respawn_policy: RespawnPolicy | None = None,
        *,
        all_processes: bool = False,
        confined: bool = False,
        cli: LabCli | None = None,
        start_pacer: StartPacer | None = None,
    ) -> None:
        self.bus = bus
        self.packages = packages
        self.respawn_policy = respawn_policy or RespawnPolicy()
        self.launched: list[LaunchedNode] = []
        bus.crash_handlers.append(self._on_crash)
        self.transport: ProcessTransport | None = None  # set once the app's graph is on Zenoh
        self.all_processes = all_processes
        self.confined = confined
        self.supervisor = Supervisor(bus, self._on_process_exit)
        self.commands = CommandRunner(self.supervisor, self._timer_node, cli)  # a launch file's ros2 commands
        # Students' files on a server that serves others: in this sandbox, or refused (why).
        self.sandbox: Sandbox | StudentCodeRefusedError | None = None
        self._on_process_start: Callable[[ProcessNode], None] | None = None
        self.start_pacer = start_pacer
        self._timers: Node | None = None  # a hidden node for the respawns' and waiting starts' timers
        # Told of every launch file's nodes once started (server/world/checkpoints watches launches).
        self.on_launch: list[Callable[[LaunchDescription, list[LaunchedNode]], None]] = []

    def use_graph(
        self,
        transport: ProcessTransport | None,
        sandbox: Sandbox | StudentCodeRefusedError | None,
        on_process_start: Callable[[ProcessNode], None] | None = None,
    ) -> None:
        """The lab's graph is up (or could not open): where node processes find it (None: not on
        Zenoh), how students' files run (in ``sandbox``, refused and why, or None: as the server's
        user), and who is told of each node process that starts."""
        self.transport = transport
        self.sandbox = sandbox
        self._on_process_start = on_process_start
        if self.start_pacer is not None and not isinstance(sandbox, StudentCodeRefusedError):
            # A class world's Runs wait for their turn on this node's timers: made now, as the
            # world starts, rather than by its first Run, when sixty may come in the same second
            # (a node on the graph is a few ms of the loop: its tokens, /rosout, its parameters).
            self._timer_node()

    def parse(self, path: str | Path, args: Mapping[str, str] | None = None) -> LaunchDescription:
        return parse_launch(
            path, args, self.packages, confined=self.confined, run_python=self.python_launch()
        )

    def python_launch(self) -> PythonLaunchProcess:
        """How this lab evaluates a Python launch file: where its students' nodes run (in the
        sandbox on a server that serves others; refused, when one is read, where it has none)."""
        domain_id = self.transport.domain_id if self.transport is not None else 0
        if isinstance(self.sandbox, StudentCodeRefusedError):
            return PythonLaunchProcess(
                self.packages.workspace, None, self.confined, domain_id, refused=self.sandbox
            )
        return PythonLaunchProcess(self.packages.workspace, self.sandbox, self.confined, domain_id)

    def launch_file(self, path: str | Path, args: Mapping[str, str] | None = None) -> list[LaunchedNode]:
        return self.launch(self.parse(path, args))

    def launch(self, description: LaunchDescription) -> list[LaunchedNode]:
        """Start every node and command (``launch_all``); the nodes."""
        return self.launch_all(description)[0]

    def launch_all(
        self, description: LaunchDescription
    ) -> tuple[list[LaunchedNode], list[LaunchedCommand], list[str]]:
        """Start every node, then every command; StudentCodeRefusedError before any starts if a node
        is a student's file this server does not run. Also the lines saying which commands were refused."""
        if isinstance(self.sandbox, StudentCodeRefusedError):
            for action in description.nodes:
                with contextlib.suppress(LookupError):
                    self.check_student_code(self.packages.resolve(action.pkg, action.exec))
        started = [self.start(a) if a.start_delay_s <= 0 else self._start_after(a) for a in description.nodes]
        self.launched.extend(started)
        commands, refused = self.commands.start_all(description.commands)
        for hook in self.on_launch:
            hook(description, started)
        return started, commands, refused

    def _start_after(self, action: NodeAction) -> LaunchedNode:
        """A node a TimerAction holds back: started ``start_delay_s`` later, unless its launch was
        stopped first."""
        entry = LaunchedNode(action)

        def start() -> None:
            timer.cancel()
            if any(e is entry for e in self.launched):  # not stopped meanwhile
                self.start(action, entry)

        timer = self._timer_node().create_timer(action.start_delay_s, start)
        return entry

    def runs_as_process(self, exe: Executable) -> bool:
        return exe.file is not None or (self.all_processes and (exe.pkg, exe.name) not in DEVICE_NODES)

    def check_student_code(self, exe: Executable) -> None:
        """StudentCodeRefusedError if ``exe`` is a student's file and this server cannot sandbox it."""
        if exe.file is not None and isinstance(self.sandbox, StudentCodeRefusedError):
            raise self.sandbox

    def _start_process(self, action: NodeAction, exe: Executable, entry: LaunchedNode) -> LaunchedNode:
        if self.transport is None:
            raise NoGraphError(str(exe.file or f"{exe.pkg} {exe.name}"))
        self.check_student_code(exe)
        sandbox = self.sandbox if exe.file is not None and isinstance(self.sandbox, Sandbox) else None
        files = [f.path for f in action.parameter_files]
        ros = ros_args(action.name, action.namespace, action.parameters, action.remappings, files)
        command = node_command(
            exe.target,
            [*action.arguments, *with_ros_arguments(ros, action.ros_arguments)],
            router=INSIDE_ROUTER if sandbox else self.transport.router,
            domain_id=self.transport.domain_id,
            login=self.transport.login,
            workspace=self.packages.workspace,
            env={} if sandbox else None,
        )
        if sandbox is not None:
            command = sandbox.wrap(command, self.packages.workspace)
        process = self.supervisor.prepare(
            command, action.exec, screen=action.output in SCREEN_OUTPUTS, node_name=action.name
        )
        entry.process, entry.node, entry.error = process, None, None
        pacer = self.start_pacer if exe.file is not None else None
        turn = pacer.admit(NEW_TURN, self.bus.label or "") if pacer is not None else None
        if turn is None:
            try:
                self._spawn(process)
            except OSError:
                entry.process = None
                raise
        else:
            self._start_later(entry, process, turn)
        if action.respawn:
            entry.respawn = entry.respawn or RespawnBackoff(self.respawn_policy, self.bus.clock)
            entry.respawn.started()
        return entry

    def _spawn(self, process: ProcessNode) -> None:
        self.supervisor.spawn(process)
        if self._on_process_start is not None:
            self._on_process_start(process)

    def _start_later(self, entry: LaunchedNode, process: ProcessNode, turn: Turn) -> None:
        """Start ``process`` at its turn (asking the pacer again then, with the turn's ticket),
        unless stopped before."""
        log.info(
            "%s: waiting %.1f s for its turn to start (node processes start a few at a time here)",
            self.bus.tagged(f"[{process.label}]"),
            turn.wait_s,
        )

        def at_turn() -> None:
            timer.cancel()
            if process.state != "waiting" or entry.process is not process:
                return  # stopped (or started again) while it waited
            pacer = self.start_pacer
            again = pacer.admit(turn.ticket or NEW_TURN, self.bus.label or "") if pacer is not None else None
            if again is not None:
                self._start_later(entry, process, again)
                return
            try:
                self._spawn(process)
            except OSError as exc:
                entry.process, entry.error = None, f"{type(exc).__name__}: {exc}"
                log.error(
                    "%s: node %s (%s %s) failed to start: %s",
                    entry.action.location,
                    entry.action.name or entry.action.exec,
                    entry.action.pkg,
                    entry.action.exec,
                    entry.error,
                )

        timer = self._timer_node().create_timer(turn.wait_s, at_turn)

    def _timer_node(self) -> Node:
        if self._timers is None:
            with self.bus.activate():
                self._timers = Node("_launch_timers")
        return self._timers

    def start(
        self, action: NodeAction, entry: LaunchedNode | None = None, exe: Executable | None = None
    ) -> LaunchedNode:
        """Start the node: inside the app, or as its own process (a student's file; every lab node
        with ``all_processes``). A failure is recorded and logged, and the rest of the graph runs on.
        ``exe``: what the action names, resolved just now by the caller (a student's package is
        found on disk: a Run resolves it once, not twice)."""
        entry = entry or LaunchedNode(action)
        entry.starts += 1
        try:
            exe = exe or self.packages.resolve(action.pkg, action.exec)
            if self.runs_as_process(exe):
                return self._start_process(action, exe, entry)
        except (LookupError, NoGraphError, OSError) as exc:
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
        overrides = NodeOverrides(
            name=action.name,
            namespace=action.namespace,
            parameters=dict(action.parameters),
            remappings=dict(action.remappings),
            files=action.parameter_files,
        )
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
        serve_parameters(node)
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
        if entry.process is not None:
            self.supervisor.stop_soon(entry.process)
            self.supervisor.forget(entry.process)
            entry.process = None

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
        self.supervisor.stop_all()  # every node and command process at once, and wait for them
        self.commands.running.clear()
        for entry in reversed(self.launched):
            self.stop(entry)
        self.launched.clear()
        if self._timers is not None:
            self._timers.destroy_node()
            self._timers = None

    def _on_process_exit(self, process: ProcessNode) -> None:
        entry = next((e for e in self.launched if e.process is process), None)
        if entry is None:
            return
        entry.error = f"died (exit code {process.exit_code})"
        if entry.action.respawn:
            self._schedule_respawn(entry, entry.process_label())

    def _on_crash(self, node: Node, exc: BaseException) -> None:
        entry = next((e for e in self.launched if e.node is node), None)
        if entry is None or not entry.action.respawn:
            return
        self._schedule_respawn(entry, node.fully_qualified_name)

    def _schedule_respawn(self, entry: LaunchedNode, who: str) -> None:
        if entry.respawn is None:
            entry.respawn = RespawnBackoff(self.respawn_policy, self.bus.clock)
        delay = entry.respawn.crashed(entry.action.respawn_delay_s)
        who = self.bus.tagged(who)
        if delay is None:
            log.error(
                "%s crashed %d times soon after starting; no more respawns",
                who,
                entry.respawn.fast_failures - 1,
            )
            return
        log.warning("%s crashed; respawning in %.2f s", who, delay)

        def respawn() -> None:
            timer.cancel()
            self.stop(entry)
            self.start(entry.action, entry)

        timer = self._timer_node().create_timer(delay, respawn)
