"""A lab server as a child process on a free loopback port, for the benches that measure it from
outside: start, wait until healthy, read its memory, stop it by its own id; and a student's join
to a class server, followed through the class's join queue."""

from __future__ import annotations

import json
import os
import re
import signal
import socket
import subprocess
import sys
import threading
import time
from pathlib import Path
from typing import IO, Any

import httpx

READY_TIMEOUT_S = 60.0
# The benches' readings while they measure: one client that keeps its connections. httpx.get
# builds a client and a TLS context per call (about 55 ms of CPU each, against 4 ms), which the
# server measured on the same cores would pay for.
READER = httpx.Client(timeout=60)
STOP_TIMEOUT_S = 10.0


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


def end(proc: subprocess.Popen[Any], timeout_s: float = STOP_TIMEOUT_S, sig: int = signal.SIGINT) -> None:
    """Ctrl-C (or ``sig``) to this process, by its id; killed if it does not stop in time."""
    if proc.poll() is None:
        proc.send_signal(sig)
        try:
            proc.wait(timeout=timeout_s)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait(timeout=timeout_s)


def cpu_s(pid: int) -> float:
    """utime + stime of the whole process (all its threads) so far, in seconds."""
    stat = Path(f"/proc/{pid}/stat").read_text()
    fields = stat[stat.rindex(")") + 2 :].split()  # the command name may hold spaces
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def rss_mib(pid: int) -> float:
    """VmRSS of the process, in MiB."""
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024.0
    raise RuntimeError(f"no VmRSS for pid {pid}")


class FrameReader:
    """A WebSocket read on a thread of its own: every frame with when it came here, as
    (CLOCK_REALTIME ns, CLOCK_MONOTONIC ns, frame decoded from JSON)."""

    def __init__(self, url: str, headers: dict[str, str] | None = None) -> None:
        from websockets.sync.client import connect

        self.ws = connect(url, max_size=None, additional_headers=headers)
        self._frames: list[tuple[int, int, Any]] = []
        self._lock = threading.Lock()
        self.last_monotonic_ns = time.monotonic_ns()
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._read, daemon=True)
        self._thread.start()

    def _read(self) -> None:
        while not self._stop.is_set():
            try:
                text = self.ws.recv(timeout=0.2)
            except TimeoutError:
                continue
            except Exception:  # closed
                return
            wall_ns, mono_ns = time.time_ns(), time.monotonic_ns()
            frame = json.loads(text)
            with self._lock:
                self._frames.append((wall_ns, mono_ns, frame))
                self.last_monotonic_ns = mono_ns

    def frames(self, since: int = 0) -> list[tuple[int, int, Any]]:
        with self._lock:
            return self._frames[since:]

    def count(self) -> int:
        with self._lock:
            return len(self._frames)

    def close(self) -> None:
        self._stop.set()
        self._thread.join(timeout=5)
        self.ws.close()


class LiveServer:
    """``python -m server --launch LAUNCH ARGS`` in ``workdir``, its output in ``workdir/server.log``."""

    def __init__(self, workdir: Path, launch: str, *launch_args: str) -> None:
        self.port, self.zenoh_port = free_port(), free_port()
        self.url = f"http://127.0.0.1:{self.port}"
        self.ws_url = f"ws://127.0.0.1:{self.port}"
        self.log_path = workdir / "server.log"
        self._log: IO[bytes] = self.log_path.open("wb")
        self.proc = subprocess.Popen(
            [
                sys.executable,
                "-m",
                "server",
                "--port",
                str(self.port),
                "--zenoh-listen",
                f"tcp/127.0.0.1:{self.zenoh_port}",
                "--launch",
                launch,
                *launch_args,
            ],
            cwd=workdir,
            stdout=self._log,
            stderr=subprocess.STDOUT,
            env={"PYTHONPATH": str(Path(__file__).resolve().parent.parent), "PATH": "/usr/bin:/bin"},
        )
        deadline = time.monotonic() + READY_TIMEOUT_S
        while not self._healthy():
            if self.proc.poll() is not None or time.monotonic() > deadline:
                self.stop()
                raise RuntimeError(f"the server did not come up:\n{self.log_path.read_text()[-3000:]}")
            time.sleep(0.1)

    def _healthy(self) -> bool:
        try:
            return httpx.get(f"{self.url}/api/health", timeout=1.0).status_code == 200
        except httpx.HTTPError:
            return False

    def rss_mib(self) -> float:
        return rss_mib(self.proc.pid)

    def instructor_token(self) -> str:
        """The instructor's token of a class server, from the link it printed when it started."""
        found = re.search(r"/instructor\?token=(\S+)", self.log_path.read_text())
        if found is None:
            raise RuntimeError("the class server printed no instructor's link")
        return found.group(1)

    def log_problems(self) -> list[str]:
        """Lines of the server's log that report an error or a traceback."""
        lines = self.log_path.read_text(errors="replace").splitlines()
        return [line for line in lines if " ERROR " in line or "Traceback" in line or "Exception" in line]

    def stop(self) -> None:
        end(self.proc)
        self._log.close()


def class_join(url: str, name: str, code: str, wait_s: float, timeout_s: float = 30.0) -> httpx.Response:
    """``POST /api/classroom/join`` as student ``name``; a join the class server queues at its
    capacity (202, a ticket) is polled as the page polls it, and one refused for the joins from this
    address (429, every bench student joins from 127.0.0.1) is sent again after its Retry-After,
    for at most ``wait_s``. The last answer: 201 with the world's token once admitted, else what the
    class server said (202 if still waiting)."""
    deadline = time.monotonic() + wait_s
    reply = httpx.post(f"{url}/api/classroom/join", json={"name": name, "code": code}, timeout=timeout_s)
    while reply.status_code == 429 and "Retry-After" in reply.headers and time.monotonic() < deadline:
        time.sleep(float(reply.headers["Retry-After"]))
        reply = httpx.post(f"{url}/api/classroom/join", json={"name": name, "code": code}, timeout=timeout_s)
    while reply.status_code == 202 and time.monotonic() < deadline:
        time.sleep(float(reply.json().get("poll_s", 2.0)))
        reply = httpx.get(f"{url}/api/classroom/join/{reply.json()['ticket']}", timeout=timeout_s)
    return reply
