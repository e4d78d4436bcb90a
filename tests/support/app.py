"""The real app in a subprocess (its HTTP port and Zenoh router on free loopback ports), and helper
processes that speak JSON lines; every process is ended by its own id."""

from __future__ import annotations

import json
import os
import queue
import random
import re
import signal
import socket
import subprocess
import threading
import time
from collections import deque
from collections.abc import Callable
from pathlib import Path
from typing import IO, Any

import httpx
import pytest

from support.forked_server import ForkedProcess, ServerProcess, start_server
from support.http import HTTP
from support.wait import wait_until

REPO = Path(__file__).resolve().parents[2]
READY_S = 40.0
WAIT_S = 20.0


def _ephemeral_low() -> int:
    """The lowest port the kernel hands out by itself (for bind to 0 and outgoing connections)."""
    try:
        return int(Path("/proc/sys/net/ipv4/ip_local_port_range").read_text().split()[0])
    except (OSError, ValueError, IndexError):
        return 32768


_HANDED_OUT: deque[int] = deque(maxlen=1024)  # the ports free_ports gave lately, newest last


def _own_range(low: int, high: int) -> tuple[int, int]:
    """This pytest-xdist worker's share of the ports ``low`` to ``high``: each worker picks from
    its own slice, so a port one worker picked and has not bound yet is never picked by another
    (with shared ports that happened about once a run: a server failed with "address already in
    use")."""
    worker = os.environ.get("PYTEST_XDIST_WORKER", "")
    count = int(os.environ.get("PYTEST_XDIST_WORKER_COUNT", "1") or 1)
    if not worker.startswith("gw") or not worker[2:].isdigit() or count < 2:
        return low, high
    size = (high - low) // count
    start = low + int(worker[2:]) % count * size
    return start, start + size


def free_ports(count: int) -> list[int]:
    """``count`` distinct loopback ports that are free now, picked below the kernel's ephemeral
    range: a port the kernel gives out by itself (to a Zenoh session or WebSocket server the app
    binds to port 0, or to any outgoing connection) can then never be one a test hands the app.
    All are held until all are picked, so two never come out the same; each xdist worker picks
    from a slice of its own; and a port this process handed out lately is not handed out again
    (a test that picks its bridges' ports, then starts an App that picks its own, once got the
    same port twice before either was bound: "address already in use")."""
    low, high = _own_range(20000, _ephemeral_low())
    rng = random.Random()
    held: list[socket.socket] = []
    try:
        for _ in range(200 * count):
            if len(held) == count:
                break
            port = rng.randrange(low, high) if high > low + count else 0
            if port in _HANDED_OUT:
                continue
            sock = socket.socket()
            try:
                sock.bind(("127.0.0.1", port))
            except OSError:
                sock.close()
                continue
            held.append(sock)
        if len(held) < count:
            raise RuntimeError(f"found only {len(held)} of {count} free loopback ports")
        ports = [int(sock.getsockname()[1]) for sock in held]
        _HANDED_OUT.extend(ports)
        return ports
    finally:
        for sock in held:
            sock.close()


def free_port() -> int:
    return free_ports(1)[0]


def end(proc: subprocess.Popen[Any] | ForkedProcess, timeout_s: float = 10.0) -> None:
    """Ctrl-C, then a kill if it does not stop in time."""
    if proc.poll() is None:
        proc.send_signal(signal.SIGINT)
        try:
            proc.wait(timeout=timeout_s)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait(timeout=timeout_s)


def healthy(url: str) -> bool:
    try:
        return HTTP.get(f"{url}/api/health", timeout=1.0).status_code == 200
    except httpx.HTTPError:
        return False


def wait_healthy(url: str, proc: ServerProcess, timeout_s: float, log_tail: Callable[[], str]) -> None:
    """Until the app at ``url`` answers /api/health; the test fails, with the log's tail, if its
    process ends first or ``timeout_s`` passes."""

    def up() -> bool:
        if proc.poll() is not None:
            pytest.fail(f"the app ended (code {proc.returncode}) before it came up:\n{log_tail()}")
        return healthy(url)

    wait_until(up, "the app to answer /api/health", timeout_s, poll_s=0.1, detail=log_tail)


def own_state(workdir: Path, args: tuple[str, ...] | list[str]) -> list[str]:
    """``--state-dir`` in ``workdir`` unless ``args`` name one: a test's server keeps its report key
    and its worlds' checkpoint progress there, never in a folder another test's server reads (a
    class server and its workers given one ``workdir`` share it, as they share one on a machine)."""
    return [] if "--state-dir" in args else ["--state-dir", str(workdir / "state")]


class LoggedProcess:
    """A ``python -m server`` process whose output goes to ``log_path``; ``stop`` ends it by its id."""

    proc: ServerProcess
    log_path: Path
    _log: IO[str]

    def log_tail(self, chars: int = 3000) -> str:
        self._log.flush()
        return self.log_path.read_text(errors="replace")[-chars:]

    def stop(self) -> None:
        end(self.proc)
        self._log.close()


class App(LoggedProcess):
    """``python -m server`` with a Zenoh router of its own, run in ``cwd`` (its ./workspace)."""

    def __init__(
        self, workdir: Path, *launch: str, cwd: Path | None = None, ready_s: float = READY_S
    ) -> None:
        self.port, self.zenoh_port = free_ports(2)
        self.url = f"http://127.0.0.1:{self.port}"
        self.router = f"127.0.0.1:{self.zenoh_port}"
        self.log_path = workdir / "app.log"
        self._log = self.log_path.open("w")
        self.proc = start_server(
            ["--host", "127.0.0.1", "--port", str(self.port), "--zenoh-listen", f"tcp/{self.router}",
             *own_state(workdir, launch), *launch],
            cwd=cwd or REPO, log=self.log_path,
        )  # fmt: skip
        try:
            wait_healthy(self.url, self.proc, ready_s, self.log_tail)
        except BaseException:  # the test fails here, and has no App to stop: end the process now
            self.stop()
            raise

    def get(self, path: str, **params: Any) -> Any:
        response = HTTP.get(self.url + path, params=params, timeout=5.0)
        response.raise_for_status()
        return response.json()

    def post(self, path: str, body: dict[str, Any]) -> httpx.Response:
        return HTTP.post(self.url + path, json=body, timeout=30.0)

    def delete(self, path: str) -> httpx.Response:
        return HTTP.delete(self.url + path, timeout=30.0)

    def wait_for(self, condition: Callable[[], bool], what: str, timeout_s: float = WAIT_S) -> None:
        wait_until(condition, what, timeout_s, poll_s=0.05, detail=self.log_tail)


class JsonProcess:
    """A helper process that takes JSON lines on stdin and answers with JSON lines on stdout."""

    def __init__(self, args: list[str], env: dict[str, str] | None = None) -> None:
        self.proc = subprocess.Popen(
            args, cwd=REPO, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
            text=True, env={**os.environ, **(env or {})},
        )  # fmt: skip
        self.events: queue.Queue[dict[str, Any] | None] = queue.Queue()
        self.seen: list[dict[str, Any]] = []
        self.stderr: list[str] = []
        self._readers = [
            threading.Thread(target=self._pump, args=(self.proc.stdout,), daemon=True),
            threading.Thread(target=self._errors, args=(self.proc.stderr,), daemon=True),
        ]
        for reader in self._readers:
            reader.start()

    def _pump(self, stream: IO[str] | None) -> None:
        assert stream is not None
        for line in stream:
            try:
                self.events.put(json.loads(line))
            except json.JSONDecodeError:
                self.stderr.append(line)
        self.events.put(None)

    def _errors(self, stream: IO[str] | None) -> None:
        assert stream is not None
        for line in stream:
            self.stderr.append(line)

    def send(self, **command: Any) -> None:
        assert self.proc.stdin is not None
        self.proc.stdin.write(json.dumps(command) + "\n")
        self.proc.stdin.flush()

    def expect(
        self, predicate: Callable[[dict[str, Any]], bool], what: str, timeout_s: float = WAIT_S
    ) -> dict[str, Any]:
        """The first event (from now on, or already seen) for which ``predicate`` holds."""
        for event in self.seen:
            if predicate(event):
                return event
        deadline = time.monotonic() + timeout_s
        while True:
            try:
                event = self.events.get(timeout=max(0.0, deadline - time.monotonic()))
            except queue.Empty:
                pytest.fail(
                    f"no {what} within {timeout_s} s; saw {self.seen[-10:]}; stderr {self.stderr[-10:]}"
                )
            if event is None:
                pytest.fail(f"the process ended before {what}; stderr:\n{''.join(self.stderr[-30:])}")
            self.seen.append(event)
            if event.get("event") == "error":
                pytest.fail(f"the peer failed: {event}")
            if predicate(event):
                return event

    def newest(self, predicate: Callable[[dict[str, Any]], bool]) -> dict[str, Any] | None:
        """The newest event so far for which ``predicate`` holds (what has queued up is read first)."""
        while True:
            try:
                event = self.events.get_nowait()
            except queue.Empty:
                break
            if event is not None:
                self.seen.append(event)
        return next((e for e in reversed(self.seen) if predicate(e)), None)

    def kill(self) -> None:
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait(timeout=10)

    def stop(self) -> None:
        if self.proc.poll() is None:
            try:
                self.send(cmd="quit")
                self.proc.wait(timeout=5)
            except (BrokenPipeError, subprocess.TimeoutExpired):
                self.kill()
        for reader in self._readers:  # they end at the pipes' end of file, once the process is gone
            reader.join(timeout=5)
        for stream in (self.proc.stdin, self.proc.stdout, self.proc.stderr):
            if stream is not None:
                stream.close()


def instructor_token(log_text: str) -> str:
    """The instructor's token from the link a class server prints once at start."""
    found = re.search(r"/instructor\?token=(\S+)", log_text)
    if found is None:
        pytest.fail(f"the class server printed no instructor's link:\n{log_text[-2000:]}")
    return found.group(1)


class WorldWorker(LoggedProcess):
    """``ros2lab world-worker`` in a subprocess, joined to a class server's Zenoh router."""

    def __init__(
        self,
        workdir: Path,
        router: str,
        class_token: str,
        worker_id: str,
        *extra: str,
        cwd: Path | None = None,
    ) -> None:
        self.id = worker_id
        self.log_path = workdir / f"worker-{worker_id}.log"
        self._log = self.log_path.open("w")
        self.proc = start_server(
            [
                "world-worker",
                "--connect",
                f"tcp/{router}",
                "--id",
                worker_id,
                *own_state(workdir, extra),
                *extra,
            ],
            cwd=cwd or REPO,
            log=self.log_path,
            env={**os.environ, "ROS2LAB_TOKEN": class_token},
        )


def wait_for_workers(url: str, token: str, ids: set[str], timeout_s: float = READY_S) -> list[dict[str, Any]]:
    """Until the class server at ``url`` finds every worker in ``ids`` on its router."""

    def found() -> list[dict[str, Any]] | None:
        reply = HTTP.get(
            f"{url}/api/classroom/workers", headers={"Authorization": f"Bearer {token}"}, timeout=10
        )
        seen: list[dict[str, Any]] = reply.json()["workers"] if reply.status_code == 200 else []
        return seen if ids <= {w["id"] for w in seen} else None

    return wait_until(found, f"the class server to find workers {sorted(ids)}", timeout_s, poll_s=0.2)
