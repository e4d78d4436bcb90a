"""``python -m server`` started by a fork of a process that has imported the app already.

A server's start is mostly imports: of the 1.2 CPU seconds a fly lab takes to answer /api/health,
forking skips about 1.0 (bench/server_start.py), the imports of FastAPI, pydantic, viser, Zenoh,
numpy and the app's own modules; and the suite starts dozens of servers on two cores. So each pytest process keeps one *starter*: this file run as a program, which
imports those modules once and then, for every server a test asks for, forks a child that runs
``server/__main__.py`` as ``python -m server ARGS`` would (``sys.argv``, the working folder, the
environment, stdin from /dev/null, stdout and stderr to the test's log file, Ctrl-C as
KeyboardInterrupt) and exits through the interpreter's normal shutdown. What runs is the app's
own code from its entry point on, in a process of its own; only the imports it would repeat are
inherited.

The test side holds a ``ForkedProcess``, which answers as much of ``subprocess.Popen`` as the tests
use (``pid``, ``poll``, ``wait``, ``send_signal``, ``terminate``, ``kill``, ``returncode``). The
starter is the child's parent, so it reaps the child and reports the exit code, and it sends the
signals a test asks for only to a child it has not reaped yet, so a signal can never reach a
process that later took the same id. When its pytest process ends (or dies), the starter's stdin
closes; it kills the children still running, reaps them and exits. (``ps`` shows a forked server
with the starter's command line, ``python tests/support/forked_server.py``: look for its children.)

``TELEOP_TEST_FORK=0`` starts every server with ``subprocess.Popen`` instead.
"""

from __future__ import annotations

import atexit
import json
import os
import selectors
import signal
import subprocess
import sys
import threading
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parents[2]
SERVER_MAIN = REPO / "server" / "__main__.py"
# What a server has imported by the time it answers /api/health (its entry point, the app, uvicorn's
# loop and protocols); a module missing here is imported by the child itself, as it would be anyway.
PRELOAD = (
    "server.__main__", "server.serve", "server.app", "server.world.lab", "server.classroom",
    "server.services.bridges", "server.host.processes", "uvicorn", "uvicorn.loops.auto", "uvicorn.protocols.http.auto",
    "uvicorn.protocols.websockets.auto", "uvicorn.lifespan.on", "viser", "zenoh", "numpy", "rich",
)  # fmt: skip
START_S = 60.0  # the starter's imports: about 1 s on a quiet 2-core machine


def enabled() -> bool:
    return os.environ.get("TELEOP_TEST_FORK", "1") != "0"


# ---- the starter (this file run as a program) ----


class _RunServer(Exception):
    """Raised in a fresh child to leave the starter's loop and run the server at the top level."""


def _child(request: dict[str, Any], closing: list[int]) -> None:
    """In the child just forked: become ``python -m server ARGS`` in ``request['cwd']``."""
    signal.set_wakeup_fd(-1)
    for fd in closing:
        os.close(fd)
    for sig in (signal.SIGCHLD, signal.SIGTERM, signal.SIGHUP):
        signal.signal(sig, signal.SIG_DFL)
    signal.signal(signal.SIGINT, signal.default_int_handler)
    log = os.open(request["log"], os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o644)
    null = os.open(os.devnull, os.O_RDONLY)
    os.dup2(null, 0)
    os.dup2(log, 1)
    os.dup2(log, 2)
    os.close(log)
    os.close(null)
    os.chdir(request["cwd"])
    os.environ.clear()
    os.environ.update(request["env"])
    sys.argv = [str(SERVER_MAIN), *request["args"]]
    sys.path[0] = os.getcwd()  # as ``python -m`` puts the working folder first
    raise _RunServer


def _serve_forks() -> None:
    """Import the app, then fork a server for each request on stdin until stdin closes."""
    replies = os.dup(1)
    null = os.open(os.devnull, os.O_WRONLY)
    os.dup2(null, 1)  # nothing but the replies reaches the test, and no child inherits that pipe
    os.close(null)
    for name in PRELOAD:
        __import__(name)
    # Run as a program, with the repository first on sys.path (below): tests/ is no package there.
    from tests.support.child_reaping import drain, end_all, reaped, wake_on_child_exit

    wake_r, wake_w = wake_on_child_exit()
    children: set[int] = set()

    def reply(message: dict[str, Any]) -> None:
        os.write(replies, (json.dumps(message) + "\n").encode())

    def reap() -> None:
        for pid, code in reaped(children):
            children.discard(pid)
            reply({"op": "exit", "pid": pid, "code": code})

    reply({"op": "ready"})
    selector = selectors.DefaultSelector()
    selector.register(0, selectors.EVENT_READ)
    selector.register(wake_r, selectors.EVENT_READ)
    pending = b""
    while True:
        for key, _ in selector.select():
            if key.fd == wake_r:
                drain(wake_r)
                reap()
                continue
            chunk = os.read(0, 65536)
            if not chunk:  # the pytest process has gone: end what it left running
                end_all(children)
                return
            pending += chunk
            while b"\n" in pending:
                line, pending = pending.split(b"\n", 1)
                request = json.loads(line)
                if request["op"] == "start":
                    sys.stdout.flush()
                    sys.stderr.flush()
                    pid = os.fork()
                    if pid == 0:
                        selector.close()
                        _child(request, [replies, wake_r, wake_w])
                    children.add(pid)
                    reply({"op": "started", "pid": pid})
                elif request["op"] == "signal":
                    sent = request["pid"] in children
                    if sent:
                        os.kill(request["pid"], request["sig"])
                    reply({"op": "signalled", "sent": sent})
        reap()


# ---- the test's side ----


class ForkedProcess:
    """A server the starter forked: the part of ``subprocess.Popen`` the tests use."""

    def __init__(self, starter: Starter, pid: int, args: list[str]) -> None:
        self._starter = starter
        self.pid = pid
        self.args = args
        self.returncode: int | None = None

    def poll(self) -> int | None:
        if self.returncode is None:
            self.returncode = self._starter.exit_code(self.pid, 0.0)
        return self.returncode

    def wait(self, timeout: float | None = None) -> int:
        if self.returncode is None:
            self.returncode = self._starter.exit_code(self.pid, timeout)
            if self.returncode is None:
                raise subprocess.TimeoutExpired(self.args, timeout or 0.0)
        return self.returncode

    def send_signal(self, sig: int) -> None:
        if self.returncode is None:
            self._starter.signal(self.pid, sig)

    def terminate(self) -> None:
        self.send_signal(signal.SIGTERM)

    def kill(self) -> None:
        self.send_signal(signal.SIGKILL)


class Starter:
    """The test process's one starter, and what it has said about its children."""

    def __init__(self) -> None:
        self.proc = subprocess.Popen(
            [sys.executable, __file__], cwd=REPO, stdin=subprocess.PIPE, stdout=subprocess.PIPE
        )
        self._lock = threading.Lock()  # one request and its reply at a time
        self._changed = threading.Condition()
        self._replies: list[dict[str, Any]] = []
        self._exits: dict[int, int] = {}
        self._gone = False
        self._reader = threading.Thread(target=self._read, name="forked-server-replies", daemon=True)
        self._reader.start()
        self._await("ready", START_S)

    def _read(self) -> None:
        assert self.proc.stdout is not None
        for line in self.proc.stdout:
            message = json.loads(line)
            with self._changed:
                if message["op"] == "exit":
                    self._exits[message["pid"]] = message["code"]
                else:
                    self._replies.append(message)
                self._changed.notify_all()
        with self._changed:
            self._gone = True
            self._changed.notify_all()

    def _await(self, op: str, timeout_s: float) -> dict[str, Any]:
        with self._changed:
            if not self._changed.wait_for(lambda: self._replies or self._gone, timeout_s):
                raise RuntimeError(f"the server starter sent no {op!r} within {timeout_s} s")
            if not self._replies:
                raise RuntimeError(f"the server starter ended (code {self.proc.poll()}) before {op!r}")
            message = self._replies.pop(0)
        if message["op"] != op:
            raise RuntimeError(f"the server starter answered {message} where {op!r} was due")
        return message

    def _ask(self, request: dict[str, Any], op: str) -> dict[str, Any]:
        assert self.proc.stdin is not None
        with self._lock:
            self.proc.stdin.write((json.dumps(request) + "\n").encode())
            self.proc.stdin.flush()
            return self._await(op, START_S)

    def start(self, args: list[str], cwd: Path, log: Path, env: dict[str, str]) -> ForkedProcess:
        request = {"op": "start", "args": args, "cwd": str(cwd), "log": str(log), "env": env}
        return ForkedProcess(self, int(self._ask(request, "started")["pid"]), args)

    def signal(self, pid: int, sig: int) -> None:
        self._ask({"op": "signal", "pid": pid, "sig": int(sig)}, "signalled")

    def exit_code(self, pid: int, timeout_s: float | None) -> int | None:
        with self._changed:
            self._changed.wait_for(lambda: pid in self._exits or self._gone, timeout_s)
            if pid not in self._exits and self._gone:
                raise RuntimeError(f"the server starter ended (code {self.proc.poll()}) before server {pid}")
            return self._exits.get(pid)

    def close(self) -> None:
        """Stdin closed: the starter kills its children still running, reaps them and exits."""
        if self.proc.stdin is not None:
            self.proc.stdin.close()
        try:
            self.proc.wait(timeout=30)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait(timeout=10)
        self._reader.join(timeout=10)  # it ends at the pipe's end of file
        if self.proc.stdout is not None:
            self.proc.stdout.close()


ServerProcess = ForkedProcess | subprocess.Popen[bytes]
_starter: Starter | None = None
_starting = threading.Lock()


def start_server(
    args: list[str], *, cwd: Path, log: Path, env: dict[str, str] | None = None
) -> ServerProcess:
    """``python -m server ARGS`` in ``cwd``, its output appended to ``log``, with ``env`` (default:
    this process's environment); forked from the starter unless TELEOP_TEST_FORK=0."""
    environment = dict(os.environ if env is None else env)
    log.touch()  # there to read at once, before the server writes its first line
    if not enabled():
        with log.open("a") as out:
            return subprocess.Popen(
                [sys.executable, "-m", "server", *args], cwd=cwd, stdout=out, stderr=subprocess.STDOUT,
                stdin=subprocess.DEVNULL, env=environment,
            )  # fmt: skip
    global _starter
    with _starting:
        if _starter is None:
            _starter = Starter()
            atexit.register(_starter.close)
    return _starter.start(args, cwd, log, environment)


if __name__ == "__main__":
    sys.path[0] = str(REPO)  # not this folder, whose http.py would stand in for the standard library's
    try:
        _serve_forks()
    except _RunServer:
        import runpy

        runpy.run_module("server", run_name="__main__", alter_sys=True)
