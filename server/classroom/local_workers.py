"""World workers a class server starts on its own machine (``--workers``).

A class server runs its own worlds in one Python thread, so on its own it uses about one core. By
default (``--workers auto``) it starts ``ros2lab world-worker`` processes next to itself as the
class grows, joined to its own Zenoh router: one each ``--spread-at`` worlds (10), at most one per
spare core (the cores it may run on, less its own). A class of a few students then costs one
process and starts at once, and a large class spreads over the machine. ``--workers N`` starts N
at once instead, and ``--workers 0`` none. They are ordinary world workers: placement by load, the
hello, failover and the proxy treat them as any other (``workers.py``), so the worlds that join
after a worker answers go to it until the places are even.

The class server owns them: each starts in a session of its own (a Ctrl-C in the terminal stops
the class server, which then ends them, rather than reaching every process at once), gets the
instructor's token in its environment (never on a command line another user could read), and
ends with the class server: by its id when the class server stops, or by itself when its parent
is gone (``--parent-pid``), so even a killed class server leaves none behind. One that dies is
started again (its worlds start again meanwhile, as for any worker that goes), at most
``MAX_RESTARTS`` times.
"""

from __future__ import annotations

import asyncio
import logging
import os
import signal
import subprocess
import sys
from dataclasses import dataclass, field
from pathlib import Path

from server.base.cores import usable_cores
from server.base.loop_priority import Scheduling
from server.classroom.worker_control import TOKEN_ENV
from server.host.processes.start_pacing import machine_slots_file
from server.host.settings import Settings, class_section

log = logging.getLogger("classroom.local_workers")

MAX_RESTARTS = 5  # per worker, over the class server's life: a worker that keeps dying is left down
WATCH_PERIOD_S = 1.0
STOP_WAIT_S = 5.0  # a worker ends its worlds in about a second; then it is killed


@dataclass
class _Child:
    worker_id: str
    proc: subprocess.Popen[bytes] | None = None
    restarts: int = 0
    given_up: bool = False


def spare_cores() -> int:
    """The cores this process may use (its affinity and its CPU quota), less one for itself."""
    return max(0, usable_cores() - 1)


@dataclass
class LocalWorkers:
    """World workers on this machine, joined to ``router`` (the class's own endpoint): ``count``
    at the start, and with ``spread_at`` one more each that many worlds, up to ``spare``."""

    count: int
    router: str
    class_token: str
    max_worlds: int
    workspace: Path | None
    workspaces_dir: Path  # the class's: a world moved between workers (or back) keeps its files
    bag_dir: Path
    log_level: str = "warning"
    world_log_level: str = "warning"
    loop_priority: Scheduling = "realtime"  # the class server's --loop-priority: its workers' take the same
    state_dir: Path = Path("state")  # the class server's: its worlds' progress and report key, shared
    spread_at: int | None = None  # auto: another worker each this many worlds (None: only ``count``)
    spare: int = 0  # auto: at most this many
    _children: list[_Child] = field(default_factory=list, init=False)
    _watch: asyncio.Task[None] | None = field(default=None, init=False)
    _stopping: bool = field(default=False, init=False)

    def start(self) -> None:
        """Start ``count`` workers (they join the router and answer hellos a few seconds later)."""
        self._grow_to(self.count)
        self._watch = asyncio.get_running_loop().create_task(self._watch_loop(), name="local workers")

    def spread(self, worlds: int) -> None:
        """With auto, as many workers as a class of ``worlds`` calls for: one each ``spread_at``
        worlds, at most ``spare``. Started when the class reaches the count, so the worker is
        ready for the joins after it (none when the class is full: no join would come); never
        stopped while the class server runs."""
        if self.spread_at is not None and not self._stopping and worlds < self.max_worlds:
            self._grow_to(min(self.spare, worlds // self.spread_at))

    def _grow_to(self, count: int) -> None:
        while len(self._children) < count:
            child = _Child(f"local-{len(self._children) + 1}")
            self._children.append(child)
            self._spawn(child)

    def describe(self) -> list[dict[str, object]]:
        """Each worker's id, process id (None when down) and restarts, for the instructor."""
        return [
            {
                "id": c.worker_id,
                "pid": c.proc.pid if c.proc is not None and c.proc.poll() is None else None,
                "restarts": c.restarts,
                "given_up": c.given_up,
            }
            for c in self._children
        ]

    def describe_spread(self) -> dict[str, int] | None:
        """With auto: a worker each ``at_worlds`` worlds, ``up_to`` of them; else None."""
        return None if self.spread_at is None else {"at_worlds": self.spread_at, "up_to": self.spare}

    def _command(self, child: _Child) -> list[str]:
        command = [
            sys.executable,
            "-m",
            "server",
            "world-worker",
            "--connect",
            self.router,
            "--id",
            child.worker_id,
            "--max-worlds",
            str(self.max_worlds),
            "--bag-dir",
            str(self.bag_dir.resolve()),
            "--state-dir",
            str(self.state_dir.resolve()),
            "--log-level",
            self.log_level,
            "--world-log-level",
            self.world_log_level,
            "--loop-priority",
            self.loop_priority,
            "--parent-pid",
            str(os.getpid()),
            "--start-slots",
            str(machine_slots_file(self.state_dir).resolve()),
        ]
        if self.workspace is not None:
            command += ["--workspace", str(self.workspace.resolve())]
        return [*command, "--workspaces-dir", str(self.workspaces_dir.resolve())]

    def _spawn(self, child: _Child) -> None:
        env = {**os.environ, TOKEN_ENV: self.class_token}
        try:
            child.proc = subprocess.Popen(self._command(child), env=env, start_new_session=True)
        except OSError as exc:
            log.error("world worker %s not started: %s", child.worker_id, exc)
            child.proc = None
            child.given_up = True
            return
        log.info("world worker %s started (pid %d)", child.worker_id, child.proc.pid)

    async def _watch_loop(self) -> None:
        while not self._stopping:
            await asyncio.sleep(WATCH_PERIOD_S)
            for child in self._children:
                if self._stopping or child.given_up or child.proc is None or child.proc.poll() is None:
                    continue
                code = child.proc.returncode
                if child.restarts >= MAX_RESTARTS:
                    log.error(
                        "world worker %s ended (exit %s) and has been started %d times: left down",
                        child.worker_id,
                        code,
                        child.restarts + 1,
                    )
                    child.given_up = True
                    continue
                child.restarts += 1
                log.warning(
                    "world worker %s ended (exit %s): starting it again; its worlds start again "
                    "once the class server finds it gone",
                    child.worker_id,
                    code,
                )
                self._spawn(child)

    async def stop(self) -> None:
        """End every worker by its id: a SIGTERM (it ends its worlds), then a kill if it lingers."""
        self._stopping = True
        if self._watch is not None:
            self._watch.cancel()
            await asyncio.gather(self._watch, return_exceptions=True)
            self._watch = None
        procs = [c.proc for c in self._children if c.proc is not None]
        await asyncio.to_thread(_end_all, procs)


def local_workers_for(settings: Settings, endpoint: str, class_token: str) -> LocalWorkers | None:
    """The world workers a class server on router ``endpoint`` starts on its machine, as
    ``--workers`` says (None: none, ever)."""
    klass = class_section(settings)
    spare = spare_cores() if klass.auto_workers else 0
    if klass.workers_at_start == 0 and spare == 0:
        return None
    return LocalWorkers(
        klass.workers_at_start,
        endpoint,
        class_token,
        klass.max_worlds,
        settings.lab.workspace,
        klass.workspaces_dir,
        settings.lab.bag_dir,
        world_log_level=klass.world_log_level,
        loop_priority=settings.loop_priority,
        state_dir=settings.lab.state_dir,
        spread_at=klass.spread_at if klass.auto_workers else None,
        spare=spare,
    )


def _end_all(procs: list[subprocess.Popen[bytes]]) -> None:
    for proc in procs:
        if proc.poll() is None:
            proc.send_signal(signal.SIGTERM)
    for proc in procs:
        try:
            proc.wait(timeout=STOP_WAIT_S)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait(timeout=STOP_WAIT_S)
