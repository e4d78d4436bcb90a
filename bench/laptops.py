"""Processes that stand for the students' machines on the bench's own: started by one launcher
that leads a session of its own, whose scheduling group runs at a niceness given.

Why one session: with autogroup scheduling (Linux's default on Debian and Ubuntu,
node_runtime/process/priority.py), the kernel shares the CPU between sessions first, and a
process's niceness counts only against the processes of its own session. Sixty ``ros2lab run``
at nice 10 started from the bench's session shared it with the class server, where together
they weighed more than six processes at nice 0 (60 × 110 against 1024): while their interpreters
started they took the server's share, which no class of laptops could. In a session of their own
at group niceness 10, the sixty weigh as one process at nice 10 against the class server's
session, and take the cores only as far as the class leaves them free; each one's niceness
within the session stays as it sets it (``ros2lab run`` lowers its own to the lab's).

Each process is ended by its own id (``LaptopProcess.end``); the launcher, which reaps them, by
``close``.
"""

from __future__ import annotations

import contextlib
import json
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

STOP_TIMEOUT_S = 15.0

# The launcher: leads its session (started with start_new_session), sets its group's niceness
# (its own, which its children inherit, on a kernel without autogroups), then starts each command
# it reads (one JSON line) and answers its pid; a thread reaps them.
LAUNCHER = r"""
import json, os, signal, subprocess, sys, threading, time
# Ctrl-C at its default, as a terminal's shell starts a command: a bench started in the
# background inherits SIGINT ignored, and so would every command started here, each then taking
# the whole stop timeout to end.
signal.signal(signal.SIGINT, signal.SIG_DFL)
try:
    with open("/proc/self/autogroup", "w") as group:
        group.write(sys.argv[1])
except OSError:  # no autogroups: a niceness counts against every process, so each takes this one
    os.nice(int(sys.argv[1]))

def reap():
    while True:
        try:
            os.wait()
        except ChildProcessError:
            time.sleep(0.05)

threading.Thread(target=reap, daemon=True).start()
for line in sys.stdin:
    command = json.loads(line)
    child = subprocess.Popen(
        command["argv"], env=command["env"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL
    )
    print(child.pid, flush=True)
"""


class LaptopProcess:
    """One process the launcher started: what the bench needs of a ``Popen``, by its pid."""

    def __init__(self, pid: int) -> None:
        self.pid = pid

    def poll(self) -> int | None:
        """None while it runs; 0 once it has exited (its code is the launcher's to read)."""
        try:
            stat = Path(f"/proc/{self.pid}/stat").read_text()
        except (FileNotFoundError, ProcessLookupError):
            return 0
        return 0 if stat[stat.rindex(")") + 2] == "Z" else None

    def send_signal(self, sig: int) -> None:
        if self.poll() is None:
            with contextlib.suppress(ProcessLookupError):
                os.kill(self.pid, sig)

    def end(self, timeout_s: float = STOP_TIMEOUT_S) -> None:
        """Ctrl-C, then killed if it has not exited within ``timeout_s``."""
        self.send_signal(signal.SIGINT)
        deadline = time.monotonic() + timeout_s
        while self.poll() is None and time.monotonic() < deadline:
            time.sleep(0.05)
        self.send_signal(signal.SIGKILL)


class Laptops:
    """The launcher, at group niceness ``nice`` (0 to 19)."""

    def __init__(self, nice: int) -> None:
        if not 0 <= nice <= 19:
            raise ValueError(f"a group niceness is 0 to 19, not {nice}")
        self._lock = threading.Lock()
        self.proc = subprocess.Popen(
            [sys.executable, "-c", LAUNCHER, str(nice)],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            text=True,
            start_new_session=True,
        )

    def start(self, argv: list[str], env: dict[str, str]) -> LaptopProcess:
        assert self.proc.stdin is not None and self.proc.stdout is not None
        with self._lock:
            self.proc.stdin.write(json.dumps({"argv": argv, "env": env}) + "\n")
            self.proc.stdin.flush()
            line = self.proc.stdout.readline()
        if not line.strip():
            raise RuntimeError(f"the laptops' launcher ended (exit code {self.proc.poll()})")
        return LaptopProcess(int(line))

    def close(self) -> None:
        """The launcher ended by its id (its processes first, by the caller)."""
        if self.proc.stdin is not None:
            self.proc.stdin.close()
        self.proc.send_signal(signal.SIGTERM)
        try:
            self.proc.wait(timeout=STOP_TIMEOUT_S)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait(timeout=STOP_TIMEOUT_S)
