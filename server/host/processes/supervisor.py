"""Node processes the app starts: their output, their exit, and stopping them with the app.

Like ``ros2 launch``: each process is labelled ``<executable>-<n>``; with ``output="screen"`` its
lines are printed with that label in front; its start and its death (pid, exit code) are logged.
Output is read by a thread per process, a chunk at a time, and kept (the last lines, each cut
at ``MAX_LINE_CHARS``) for the API (``GET /api/launches/{id}/output``, which ``ros2lab launch``
prints); an exit is handed to the bus's executor through a poller, so respawning happens on the
executor's thread. Stopping sends Ctrl-C (SIGINT), then SIGTERM, then SIGKILL, each after a
grace period. A sandboxed node (server/host/processes/sandbox.py) is bwrap's child: Ctrl-C goes to the
node itself, the rest to bwrap, whose end ends the sandbox.
"""

from __future__ import annotations

import contextlib
import itertools
import logging
import os
import signal
import subprocess
import sys
import threading
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import IO, Literal

from node_runtime.bus import Bus
from node_runtime.console import world_logger
from node_runtime.process import lifeline
from server.host.processes.command import RUNNER_MODULE, NodeCommand
from server.host.processes.output_lines import read_lines

log = logging.getLogger("launch")
KEEP_LINES = 200
STOP_GRACE_S = 3.0
# waiting: not started yet, its turn to come (server/host/processes/start_pacing.py)
ProcessState = Literal["waiting", "running", "died", "stopped"]
_labels = itertools.count(1)
_print_lock = threading.Lock()


@dataclass
class ProcessNode:
    """One node process: started from a ``NodeCommand``, watched until it ends."""

    command: NodeCommand
    executable: str
    screen: bool
    node_name: str | None = None  # the name it was given (a launch's name=), if any
    label: str = ""
    proc: subprocess.Popen[bytes] | None = None
    state: ProcessState = "running"
    exit_code: int | None = None
    lines: deque[str] = field(default_factory=lambda: deque(maxlen=KEEP_LINES))
    printed: int = 0  # lines it has printed in all (``lines`` keeps the last KEEP_LINES)
    finish: Callable[[int], str | None] | None = None  # called with its exit code once it has ended
    _lines_lock: threading.Lock = field(default_factory=threading.Lock, init=False, repr=False)

    def keep(self, line: str) -> None:
        """One more line it printed, as ``LineSplitter`` cut it (from its output thread)."""
        with self._lines_lock:
            self.lines.append(line)
            self.printed += 1

    def output(self) -> tuple[list[str], int]:
        """Its last lines and how many it has printed in all (a reader knows what is new)."""
        with self._lines_lock:
            return list(self.lines), self.printed

    @property
    def pid(self) -> int | None:
        return self.proc.pid if self.proc is not None else None

    def describe(self) -> dict[str, object]:
        return {"pid": self.pid, "state": self.state, "exit_code": self.exit_code, "label": self.label}


class Supervisor:
    """Starts node processes and reports their exits on the bus's executor thread."""

    def __init__(self, bus: Bus, on_exit: Callable[[ProcessNode], None]) -> None:
        self.bus = bus
        self.on_exit = on_exit
        self.processes: list[ProcessNode] = []
        self._exited: deque[ProcessNode] = deque()
        self._lock = threading.Lock()
        bus.pollers.append(self._poll)

    def start(
        self, command: NodeCommand, executable: str, *, screen: bool, node_name: str | None
    ) -> ProcessNode:
        return self.spawn(self.prepare(command, executable, screen=screen, node_name=node_name))

    def prepare(
        self, command: NodeCommand, executable: str, *, screen: bool, node_name: str | None
    ) -> ProcessNode:
        """A node process with its label, not started yet (``waiting``): ``spawn`` starts it, and
        ``stop`` before that means it never starts."""
        process = ProcessNode(
            command, executable, screen, node_name, label=f"{executable}-{next(_labels)}", state="waiting"
        )
        self.processes.append(process)
        return process

    def spawn(self, process: ProcessNode) -> ProcessNode:
        """Start a prepared process (OSError if it cannot start: it is then ``died``)."""
        if process.state != "waiting":
            raise ValueError(f"{process.label} is {process.state}, not waiting to start")
        command = process.command
        env, keep = command.env, list[int]()
        if command.sandboxed:  # its lifeline to this process: it ends when the server does
            keep.append(lifeline.read_end())
            env = {**env, lifeline.LIFELINE_ENV: str(keep[0])}
        passed: tuple[int, ...] = ()
        try:
            argv = command.argv
            if command.prepare is not None:  # a sandboxed node's control group and seccomp filter
                prepared = command.prepare(argv, process.label)
                argv, passed, process.finish = prepared.argv, prepared.pass_fds, prepared.finish
            process.proc = subprocess.Popen(
                argv,
                env=env,
                stdin=subprocess.DEVNULL,
                stdout=subprocess.PIPE,
                stderr=subprocess.STDOUT,
                pass_fds=[*keep, *passed],
            )
        except OSError:
            process.state = "died"
            self.forget(process)
            if process.finish is not None:  # what its start made (a control group) goes with it
                process.finish(-1)
            raise
        finally:
            for fd in passed:
                os.close(fd)
        process.state = "running"
        log.info("%s: process started with pid [%d]", self.bus.tagged(f"[{process.label}]"), process.proc.pid)
        threading.Thread(
            target=self._watch, args=(process,), name=f"out-{process.label}", daemon=True
        ).start()
        return process

    def _watch(self, process: ProcessNode) -> None:
        """The process's output, line by line, until it ends; then its exit, to the executor."""
        assert process.proc is not None and process.proc.stdout is not None
        stream: IO[bytes] = process.proc.stdout
        # A class world's screen lines reach the console only when its nodes' info lines do
        # (--world-log-level); they are kept for the API either way.
        echo = process.screen and (
            self.bus.label is None
            or logging.getLogger(world_logger(self.bus.label)).isEnabledFor(logging.INFO)
        )

        def line(text: str) -> None:
            process.keep(text)
            if echo:
                with _print_lock:
                    sys.stdout.write(self.bus.tagged(f"[{process.label}] {text}\n"))
                    sys.stdout.flush()

        read_lines(stream, line)
        stream.close()
        process.exit_code = process.proc.wait()
        if process.finish is not None:  # e.g. its control group says the kernel ended it for memory
            last = process.finish(process.exit_code)
            if last is not None:
                process.keep(last)
        with self._lock:
            self._exited.append(process)
        self.bus.wake_threadsafe()

    def _poll(self) -> None:
        if not self._exited:  # read without the lock: an exit that races it wakes the executor again
            return
        with self._lock:
            exited, self._exited = list(self._exited), deque()
        for process in exited:
            if process.state == "stopped":
                continue
            process.state = "died"
            code = process.exit_code
            level = logging.INFO if code == 0 else logging.ERROR
            log.log(
                level,
                "%s: process has died [pid %s, exit code %s, cmd '%s']",
                self.bus.tagged(f"[{process.label}]"),
                process.pid,
                code,
                " ".join(_node_argv(process.command)),
            )
            self.on_exit(process)

    def stop(self, process: ProcessNode, grace_s: float = STOP_GRACE_S) -> None:
        """Ctrl-C, then SIGTERM, then SIGKILL; returns once it is gone. In a sandbox the node is
        pid 1 of its namespace, which ignores a SIGTERM it has no handler for, and bwrap's end
        does not end it: past Ctrl-C it is killed itself, then bwrap ends with it."""
        process.state = "stopped"
        proc = process.proc
        if proc is None or proc.poll() is not None:
            return
        for sig in (signal.SIGINT, signal.SIGTERM):
            _send(process, sig)
            try:
                proc.wait(timeout=grace_s)
                return
            except subprocess.TimeoutExpired:
                continue
        _send(process, signal.SIGKILL)
        proc.kill()
        proc.wait()

    def stop_soon(self, process: ProcessNode) -> None:
        """Stop it without waiting here: the escalation runs on a thread of its own."""
        if process.proc is None or process.proc.poll() is not None:
            process.state = "stopped"
            return
        threading.Thread(target=self.stop, args=(process,), name=f"stop-{process.label}", daemon=True).start()

    def stop_all(self) -> None:
        """Every process, at once: Ctrl-C to all, then waits."""
        running = [p for p in self.processes if p.proc is not None and p.proc.poll() is None]
        for process in running:
            process.state = "stopped"
            _send(process, signal.SIGINT)
        for process in running:
            self.stop(process)

    def forget(self, process: ProcessNode) -> None:
        if process in self.processes:
            self.processes.remove(process)

    def by_zid(self, zid: str) -> ProcessNode | None:
        return next((p for p in self.processes if p.command.zid == zid and p.state == "running"), None)


def _node_argv(command: NodeCommand) -> list[str]:
    """What the runner runs: its arguments after the runner's module (inside bwrap's command line
    too, for a sandboxed node)."""
    if RUNNER_MODULE in command.argv:
        return command.argv[command.argv.index(RUNNER_MODULE) + 1 :]
    return command.argv


def _send(process: ProcessNode, sig: signal.Signals) -> None:
    """A signal to the node process. In a sandbox the node is the child of bwrap, pid 1 of its
    namespace: Ctrl-C and SIGKILL go to it, SIGTERM (which pid 1 ignores without a handler) kills
    it; bwrap then ends by itself."""
    proc = process.proc
    assert proc is not None
    if process.command.sandboxed and sig in (signal.SIGINT, signal.SIGTERM, signal.SIGKILL):
        inner = _child_pid(proc.pid)
        if inner is not None:
            with contextlib.suppress(ProcessLookupError):
                os.kill(inner, signal.SIGKILL if sig == signal.SIGTERM else sig)
            return
    proc.send_signal(sig)


def _child_pid(pid: int) -> int | None:
    try:
        children = Path(f"/proc/{pid}/task/{pid}/children").read_text().split()
    except OSError:
        return None
    return int(children[0]) if children else None
