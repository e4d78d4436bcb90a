"""A live lab server for the CLI's end-to-end tests, and the CLI run as a user runs it.

The server is ``python -m server --launch rocket`` in a subprocess on a free loopback port, one
for the session; each CLI call is ``python -m server <verb> ...`` in its own subprocess.
"""

from __future__ import annotations

import os
import queue
import signal
import subprocess
import threading
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import IO, Any

import pytest
from support import forked_cli
from support.app import end, free_ports, wait_healthy
from support.forked_server import ServerProcess, start_server
from support.http import HTTP
from support.wait import wait_until

SERVER_READY_S = 30.0
SERVER_STOP_S = 10.0
CLI_TIMEOUT_S = 30.0
READ_TIMEOUT_S = 10.0


@dataclass
class LiveServer:
    url: str
    proc: ServerProcess
    log_path: Path

    def log_tail(self, lines: int = 40) -> str:
        return "\n".join(self.log_path.read_text(errors="replace").splitlines()[-lines:])

    def get(self, path: str) -> Any:
        response = HTTP.get(self.url + path, timeout=5.0)
        response.raise_for_status()
        return response.json()

    def post(self, path: str, body: dict[str, Any] | None = None) -> Any:
        response = HTTP.post(self.url + path, json=body or {}, timeout=5.0)
        response.raise_for_status()
        return response.json()

    def wait_until(self, condition: Callable[[], bool], what: str, timeout_s: float = READ_TIMEOUT_S) -> None:
        """Poll the server until ``condition`` holds (a subprocess offers nothing to await)."""
        wait_until(condition, what, timeout_s, poll_s=0.05, detail=self.log_tail)


@pytest.fixture(scope="session")
def live_server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[LiveServer]:
    workdir = tmp_path_factory.mktemp("cli_server")
    port, zenoh_port = free_ports(2)
    log_path = workdir / "server.log"
    proc = start_server(
        ["--host", "127.0.0.1", "--port", str(port), "--launch", "rocket",
         "--zenoh-listen", f"tcp/127.0.0.1:{zenoh_port}", "start_delay:=0.5"],
        cwd=workdir, log=log_path,
    )  # fmt: skip
    server = LiveServer(f"http://127.0.0.1:{port}", proc, log_path)
    try:
        wait_healthy(server.url, proc, SERVER_READY_S, server.log_tail)
        yield server
    finally:
        end(proc, SERVER_STOP_S)  # Ctrl-C, as a person would; killed if it does not stop


@dataclass
class Result:
    code: int
    out: str
    err: str


def cli_command(*args: str) -> list[str]:
    return forked_cli.cli_command(*args)


def cli_env(url: str) -> dict[str, str]:
    return {**os.environ, "TELEOP_URL": url, "PYTHONUNBUFFERED": "1"}


@pytest.fixture
def ros2lab(live_server: LiveServer) -> Callable[..., Result]:
    """Run one CLI command against the live server (its URL from TELEOP_URL) to completion."""

    def run(*args: str, timeout_s: float = CLI_TIMEOUT_S) -> Result:
        done = subprocess.run(
            cli_command(*args),
            env=cli_env(live_server.url),
            capture_output=True,
            text=True,
            timeout=timeout_s,
            check=False,
        )
        return Result(done.returncode, done.stdout, done.stderr)

    return run


class Running:
    """A CLI command left running (echo, pub at a rate, launch), read line by line with a timeout."""

    def __init__(self, args: tuple[str, ...], url: str) -> None:
        self.proc = subprocess.Popen(
            cli_command(*args), env=cli_env(url), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
        )
        self.lines: queue.Queue[str | None] = queue.Queue()
        self.seen: list[str] = []
        self._pump_thread = threading.Thread(target=self._pump, args=(self.proc.stdout,), daemon=True)
        self._pump_thread.start()

    def _pump(self, stream: IO[str] | None) -> None:
        assert stream is not None
        for line in stream:
            self.lines.put(line.rstrip("\n"))
        self.lines.put(None)

    def read_until(self, predicate: Callable[[str], bool], timeout_s: float = READ_TIMEOUT_S) -> str:
        """The first output line for which ``predicate`` holds; fails on timeout or end of output."""
        deadline = time.monotonic() + timeout_s
        while True:
            try:
                line = self.lines.get(timeout=max(0.0, deadline - time.monotonic()))
            except queue.Empty:
                pytest.fail(f"no matching line within {timeout_s} s; got {self.seen[-20:]}")
            if line is None:
                pytest.fail(f"output ended without a matching line; got {self.seen[-20:]}")
            self.seen.append(line)
            if predicate(line):
                return line

    def interrupt(self, timeout_s: float = READ_TIMEOUT_S) -> tuple[int, str]:
        """Ctrl-C; returns the exit code and stderr."""
        self.proc.send_signal(signal.SIGINT)
        try:
            self.proc.wait(timeout=timeout_s)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
            pytest.fail(f"the command did not stop within {timeout_s} s of Ctrl-C")
        assert self.proc.stderr is not None
        err = self.proc.stderr.read()
        self._close_pipes()
        return self.proc.returncode, err

    def stop(self) -> None:
        """Ctrl-C, so that what it started on the server is stopped too; killed if it hangs."""
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGINT)
            try:
                self.proc.wait(timeout=READ_TIMEOUT_S)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        self._close_pipes()

    def _close_pipes(self) -> None:
        """The process has ended: let the pump reach the end of its output, then close both pipes."""
        self._pump_thread.join(timeout=READ_TIMEOUT_S)
        for stream in (self.proc.stdout, self.proc.stderr):
            if stream is not None and not stream.closed:
                stream.close()


@pytest.fixture
def start(live_server: LiveServer) -> Iterator[Callable[..., Running]]:
    """Start CLI commands that keep running; any still running at the end of the test is stopped."""
    started: list[Running] = []

    def launch(*args: str) -> Running:
        running = Running(args, live_server.url)
        started.append(running)
        return running

    yield launch
    for running in started:
        running.stop()
