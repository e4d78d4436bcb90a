"""The commands a launch file runs (``ExecuteProcess``, ``executable``): ``ros2 ...`` as the lab's own
CLI against this lab (server/services/launch/ros2_commands.py), each a process of its launch started through
the Supervisor as a node process is, so its lines show in the launch's output and stopping the launch
ends it. A command a ``TimerAction`` holds back starts that much later, on the launch timers' node.

Nothing else runs: any other program is refused with one line naming it, and so is every command on
a server that serves others (its students' code is sandboxed, and the sandbox has no way to the
lab's HTTP API, which is all the CLI talks to).
"""

from __future__ import annotations

import logging
import os
from collections.abc import Callable
from dataclasses import dataclass

from node_runtime.bus import Node
from server.host.processes.command import NodeCommand, new_zid
from server.host.processes.supervisor import ProcessNode, Supervisor
from server.services.launch.description import CommandAction
from server.services.launch.ros2_commands import PROGRAM, CommandNotRunError, cli_argv

log = logging.getLogger("launch")
TOKEN_ENV = "ROS2LAB_TOKEN"  # where the CLI finds the lab's token (never on its command line)
SCREEN_OUTPUTS = (None, "screen", "both", "full")
NOT_HERE = (
    "a launch file's commands do not run on a server that serves others (students' code runs in a "
    "sandbox, which has no way to the lab's API)"
)


@dataclass(frozen=True)
class LabCli:
    """Where a command's CLI finds this lab: its URL and, behind ``--token``, the token."""

    url: str
    token: str | None = None


@dataclass
class LaunchedCommand:
    """A command the launcher started (or is to start later, or refused)."""

    action: CommandAction
    process: ProcessNode | None = None
    error: str | None = None


class CommandRunner:
    """Starts a launch's commands; ``cli`` None: this lab runs none (a server that serves others)."""

    def __init__(self, supervisor: Supervisor, timers: Callable[[], Node], cli: LabCli | None = None) -> None:
        self.supervisor = supervisor
        self.cli = cli
        self._timers = timers
        self.running: list[LaunchedCommand] = []  # started or waiting, not stopped yet

    def argv(self, action: CommandAction) -> list[str]:
        """The CLI's command line for ``action``; CommandNotRunError (the line to show) if it is not run."""
        if self.cli is None:
            shown = " ".join(action.cmd)
            raise CommandNotRunError(f"not run: {shown!r}: {NOT_HERE}")
        return cli_argv(action.cmd, shell=action.shell, url=self.cli.url)

    def start_all(self, actions: tuple[CommandAction, ...]) -> tuple[list[LaunchedCommand], list[str]]:
        """Start (or schedule) each command; the lines to show for those refused."""
        started: list[LaunchedCommand] = []
        refused: list[str] = []
        for action in actions:
            entry = LaunchedCommand(action)
            try:
                argv = self.argv(action)
            except CommandNotRunError as exc:
                entry.error = str(exc)
                line = f"[ERROR] [launch]: {action.location}: {exc}"
                log.error("%s", line)
                refused.append(line)
                continue
            started.append(entry)
            self.running.append(entry)
            if action.start_delay_s > 0:
                self._start_after(entry, argv)
            else:
                self._start(entry, argv)
        return started, refused

    def _start_after(self, entry: LaunchedCommand, argv: list[str]) -> None:
        def start() -> None:
            timer.cancel()
            if any(e is entry for e in self.running):  # not stopped meanwhile
                self._start(entry, argv)

        timer = self._timers().create_timer(entry.action.start_delay_s, start)

    def _start(self, entry: LaunchedCommand, argv: list[str]) -> None:
        assert self.cli is not None
        env = {**os.environ, "PYTHONUNBUFFERED": "1", "PYTHONDONTWRITEBYTECODE": "1"}
        env.pop(TOKEN_ENV, None)
        if self.cli.token is not None:
            env[TOKEN_ENV] = self.cli.token
        process = self.supervisor.prepare(
            NodeCommand(argv, env, new_zid()),
            entry.action.name or PROGRAM,
            screen=entry.action.output in SCREEN_OUTPUTS,
            node_name=None,
        )
        entry.process = process
        try:
            self.supervisor.spawn(process)
        except OSError as exc:
            entry.process, entry.error = None, f"{type(exc).__name__}: {exc}"
            log.error(
                "%s: command %s failed to start: %s",
                entry.action.location,
                " ".join(entry.action.cmd),
                entry.error,
            )

    def stop(self, entries: list[LaunchedCommand]) -> None:
        """End these commands (those still running) and forget them; one waiting for its timer never starts."""
        for entry in entries:
            if entry.process is not None:
                self.supervisor.stop_soon(entry.process)
                self.supervisor.forget(entry.process)
        self.running = [e for e in self.running if e not in entries]
