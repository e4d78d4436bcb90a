"""``python -m server VERB ...`` (ros2lab's command-line verbs) forked from a process that has
imported the command line's modules already.

A verb's own work is a few HTTP calls; its start is imports. ``python -m server topic list`` took
0.55 to 0.70 CPU seconds on a 2-vCPU AMD EPYC, the same command forked from a process that had
imported those modules 0.11 to 0.17 (its own work, and the fork's copied pages), and the parallel
part of the suite runs about 220 of them, on two cores it keeps busy. So each pytest process keeps
one *CLI starter*: this file run as a program, which imports the modules ``server/__main__.py`` and
the verbs import (never ``server/__main__.py`` itself), then listens on a Unix socket.

A test runs ``cli_command(ARGS)``: ``python -S support/cli_client.py SOCKET 0|1 ARGS``, a client that
starts in a few milliseconds, with the pipes, environment and working folder the test gives it. The
client hands the starter its standard input, output and error (their descriptors, over the socket)
with its arguments, environment and folder; the starter forks a child that becomes ``python -m
server ARGS`` (``sys.argv``, the folder, the environment, fresh standard streams on those
descriptors, unbuffered for ``-u`` or PYTHONUNBUFFERED as an interpreter's would be, the random
generators seeded anew, Ctrl-C as KeyboardInterrupt) and runs ``server/__main__.py`` from its entry
point to the interpreter's normal shutdown. The client passes on each signal it gets (Ctrl-C,
SIGTERM, ...) to the child, which the starter sends only to a child it has not reaped yet, and
ends as the child ended: with its exit code, or killed by the same signal. A client killed
outright (SIGKILL, a test's timeout) closes its socket, and the starter kills the child at once,
as the command itself would have been killed. When its pytest process ends (or dies), the
starter's stdin closes; it kills the children still running, reaps them and exits.

What a test sees of the command is what a shell sees: its output, exit code, and the way it ends
on a signal. What differs is the process ids: the test's ``Popen`` holds the client, and the
command's parent is the starter. A test that reads the command's own process (its niceness, in
tests/processes/test_run_join.py) starts ``python -m server`` itself. ``TELEOP_TEST_FORK=0`` runs
every command as ``python -m server`` (as it starts every server without the server starter,
support/forked_server.py).
"""

from __future__ import annotations

import atexit
import contextlib
import io
import json
import os
import selectors
import signal
import socket
import subprocess
import sys
import tempfile
import threading
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parents[2]
SERVER_MAIN = REPO / "server" / "__main__.py"
CLIENT = Path(__file__).resolve().with_name("cli_client.py")
# What ``python -m server VERB`` imports before its verb's work: server/__main__.py's own imports,
# then the verbs' modules and their HTTP and WebSocket clients. A module missing here is imported
# by the child itself, as it would be anyway.
PRELOAD = (
    "pydantic", "node_runtime.console", "node_runtime.transport.config", "server.banner",
    "server.host.settings", "server.cli", "server.cli.client", "server.cli.action", "server.cli.bag",
    "server.cli.env", "server.cli.interface", "server.cli.launch", "server.cli.node", "server.cli.param",
    "server.cli.pkg", "server.cli.publish", "server.cli.report", "server.cli.run", "server.cli.service",
    "server.cli.topic", "httpx", "websockets.sync.client", "yaml",
)  # fmt: skip
START_S = 60.0  # the starter's imports: about half a second on a quiet 2-core machine
MAX_REQUEST = 1 << 20  # arguments and environment of one command


def enabled() -> bool:
    return os.environ.get("TELEOP_TEST_FORK", "1") != "0"


# ---- the starter (this file run as a program) ----


class _RunCommand(Exception):
    """Raised in a fresh child to leave the starter's loop and run the command at the top level."""


def _streams(env: dict[str, str], unbuffered: bool) -> None:
    """New ``sys.stdin``, ``sys.stdout`` and ``sys.stderr`` on descriptors 0, 1 and 2, made as an
    interpreter started with ``env`` makes them (the encoding PYTHONIOENCODING names, else the
    starter's own; line-buffered on a terminal; unbuffered for ``-u`` or PYTHONUNBUFFERED)."""
    unbuffered = unbuffered or bool(env.get("PYTHONUNBUFFERED"))
    named, _, named_errors = env.get("PYTHONIOENCODING", "").partition(":")
    for fd, name in ((0, "stdin"), (1, "stdout"), (2, "stderr")):
        old = getattr(sys, name)
        encoding = named or old.encoding
        errors = named_errors or old.errors
        raw = io.FileIO(fd, "r" if fd == 0 else "w", closefd=False)
        buffered: Any = raw
        if fd == 0:
            buffered = io.BufferedReader(raw)
        elif not unbuffered:
            buffered = io.BufferedWriter(raw)
        stream = io.TextIOWrapper(
            buffered,
            encoding=encoding,
            errors=errors,
            line_buffering=fd == 2 or (fd == 1 and raw.isatty()),
            write_through=unbuffered and fd != 0,
        )
        setattr(sys, name, stream)
        setattr(sys, f"__{name}__", stream)


def _child(request: dict[str, Any], fds: list[int], closing: list[int]) -> None:
    """In the child just forked: become ``python -m server ARGS`` in ``request['cwd']``."""
    signal.set_wakeup_fd(-1)
    for fd in closing:
        os.close(fd)
    for sig in (signal.SIGCHLD, signal.SIGTERM, signal.SIGHUP):
        signal.signal(sig, signal.SIG_DFL)
    signal.signal(signal.SIGINT, signal.default_int_handler)
    for target, fd in enumerate(fds):
        os.dup2(fd, target)
        os.close(fd)
    os.chdir(request["cwd"])
    os.environ.clear()
    os.environ.update(request["env"])
    _streams(request["env"], request["unbuffered"])
    for name in ("random", "numpy.random"):  # a fresh interpreter seeds them from the OS
        module = sys.modules.get(name)
        if module is not None:
            module.seed()
    sys.argv = [str(SERVER_MAIN), *request["args"]]
    sys.path[0] = os.getcwd()  # as ``python -m`` puts the working folder first
    raise _RunCommand


class _Command:
    """One client's connection, and the child it asked for."""

    def __init__(self, conn: socket.socket) -> None:
        self.conn = conn
        self.pid: int | None = None

    def send(self, message: dict[str, Any]) -> None:
        with contextlib.suppress(OSError):  # the client has gone: the child is killed on its EOF
            self.conn.send(json.dumps(message).encode())


def _serve(path: str) -> None:
    """Import the CLI's modules, then fork a command for each client until stdin closes."""
    for name in PRELOAD:
        __import__(name)
    assert threading.active_count() == 1, "a preloaded module started a thread: forks would lose it"
    # Run as a program, with the repository first on sys.path (below): tests/ is no package there.
    from tests.support.child_reaping import drain, end_all, reaped, wake_on_child_exit

    wake_r, wake_w = wake_on_child_exit()
    listener = socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET)
    listener.bind(path)
    listener.listen(64)
    selector = selectors.DefaultSelector()
    selector.register(0, selectors.EVENT_READ)
    selector.register(wake_r, selectors.EVENT_READ)
    selector.register(listener, selectors.EVENT_READ)
    by_conn: dict[int, _Command] = {}
    by_pid: dict[int, _Command] = {}
    os.write(1, b"ready\n")

    def reap() -> None:
        for pid, code in reaped(by_pid):
            command = by_pid.pop(pid, None)
            if command is not None:
                command.pid = None
                command.send({"op": "exit", "code": code})
                drop(command)

    def drop(command: _Command) -> None:
        if by_conn.pop(command.conn.fileno(), None) is not None:
            selector.unregister(command.conn)
            command.conn.close()

    def start(command: _Command) -> None:
        try:
            data, fds, _flags, _addr = socket.recv_fds(command.conn, MAX_REQUEST, 3)
        except OSError:
            data, fds = b"", []
        if not data or len(fds) != 3:  # a client that went before it asked
            for fd in fds:
                os.close(fd)
            drop(command)
            return
        sys.stdout.flush()
        sys.stderr.flush()
        pid = os.fork()
        if pid == 0:
            selector.close()
            closing = [wake_r, wake_w, listener.fileno(), *by_conn]
            _child(json.loads(data), fds, closing)
        for fd in fds:
            os.close(fd)
        command.pid = pid
        by_pid[pid] = command
        command.send({"op": "started", "pid": pid})

    def asked(command: _Command) -> None:
        """A signal to pass on, or the client's end of file (it has gone: the child is killed)."""
        try:
            data = command.conn.recv(4096)
        except OSError:
            data = b""
        if command.pid is None:
            drop(command)
            return
        sig = int(json.loads(data)["signal"]) if data else signal.SIGKILL
        os.kill(command.pid, sig)
        if not data:
            selector.unregister(command.conn)  # nothing more to read; reaped as any other
            by_conn.pop(command.conn.fileno(), None)
            command.conn.close()

    while True:
        for key, _ in selector.select():
            if key.fd == wake_r:
                drain(wake_r)
                reap()
            elif key.fd == 0:
                if os.read(0, 512):
                    continue
                end_all(by_pid)  # the pytest process has gone: end what it left running
                listener.close()
                return
            elif key.fileobj is listener:
                conn, _ = listener.accept()
                command = _Command(conn)
                by_conn[conn.fileno()] = command
                selector.register(conn, selectors.EVENT_READ, command)
            else:
                command = key.data
                if command.pid is None:
                    start(command)
                else:
                    asked(command)
        reap()


# ---- the test's side ----


class Starter:
    """The test process's one CLI starter."""

    def __init__(self) -> None:
        self.folder = tempfile.mkdtemp(prefix="ros2lab-cli-")
        self.socket = os.path.join(self.folder, "socket")
        self.proc = subprocess.Popen(
            [sys.executable, __file__, self.socket], cwd=REPO, stdin=subprocess.PIPE, stdout=subprocess.PIPE
        )
        ready: list[bytes] = []
        reader = threading.Thread(
            target=lambda: ready.append(self.proc.stdout.readline() if self.proc.stdout else b"")
        )
        reader.start()
        reader.join(START_S)
        if ready != [b"ready\n"]:
            self.close()
            raise RuntimeError(f"the CLI starter did not start within {START_S} s (code {self.proc.poll()})")

    def command(self, args: tuple[str, ...], unbuffered: bool) -> list[str]:
        return [sys.executable, "-S", str(CLIENT), self.socket, "1" if unbuffered else "0", *args]

    def close(self) -> None:
        """Stdin closed: the starter kills its children still running, reaps them and exits."""
        if self.proc.stdin is not None and not self.proc.stdin.closed:
            self.proc.stdin.close()
        try:
            self.proc.wait(timeout=30)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait(timeout=10)
        if self.proc.stdout is not None:
            self.proc.stdout.close()
        with contextlib.suppress(OSError):
            os.unlink(self.socket)
        with contextlib.suppress(OSError):
            os.rmdir(self.folder)


_starter: Starter | None = None
_starting = threading.Lock()


def starter() -> Starter:
    """This process's CLI starter, started at the first command."""
    global _starter
    with _starting:
        if _starter is None:
            _starter = Starter()
            atexit.register(_starter.close)
        return _starter


def cli_command(*args: str, unbuffered: bool = False) -> list[str]:
    """The command line of ``python -m server ARGS`` (``python -u`` with ``unbuffered``), for
    ``subprocess``: forked from this process's CLI starter unless TELEOP_TEST_FORK=0."""
    if not enabled():
        return [sys.executable, *(["-u"] if unbuffered else []), "-m", "server", *args]
    return starter().command(args, unbuffered)


if __name__ == "__main__":
    sys.path[0] = str(REPO)  # not this folder, whose http.py would stand in for the standard library's
    try:
        _serve(sys.argv[1])
    except _RunCommand:
        import runpy

        runpy.run_module("server", run_name="__main__", alter_sys=True)
