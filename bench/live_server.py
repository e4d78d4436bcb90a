"""A lab server as a child process on a free loopback port, for the benches that measure it from
outside: start, wait until healthy, read its memory, stop it by its own id."""

from __future__ import annotations

import signal
import socket
import subprocess
import sys
import time
from pathlib import Path
from typing import IO

import httpx

READY_TIMEOUT_S = 60.0
STOP_TIMEOUT_S = 10.0


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


def rss_mib(pid: int) -> float:
    """VmRSS of the process, in MiB."""
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024.0
    raise RuntimeError(f"no VmRSS for pid {pid}")


class LiveServer:
    """``python -m server --launch LAUNCH ARGS`` in ``workdir``, its output in ``workdir/server.log``."""

    def __init__(self, workdir: Path, launch: str, *launch_args: str) -> None:
        self.port, self.zenoh_port = free_port(), free_port()
        self.url = f"http://127.0.0.1:{self.port}"
        self.ws_url = f"ws://127.0.0.1:{self.port}"
        self.log_path = workdir / "server.log"
        self._log: IO[bytes] = self.log_path.open("wb")
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "server", "--port", str(self.port),
             "--zenoh-listen", f"tcp/127.0.0.1:{self.zenoh_port}", "--launch", launch, *launch_args],
            cwd=workdir, stdout=self._log, stderr=subprocess.STDOUT,
            env={"PYTHONPATH": str(Path(__file__).resolve().parent.parent), "PATH": "/usr/bin:/bin"},
        )  # fmt: skip
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

    def log_problems(self) -> list[str]:
        """Lines of the server's log that report an error or a traceback."""
        lines = self.log_path.read_text(errors="replace").splitlines()
        return [line for line in lines if " ERROR " in line or "Traceback" in line or "Exception" in line]

    def stop(self) -> None:
        """Ctrl-C to this process (by its id); killed if it does not stop in time."""
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGINT)
            try:
                self.proc.wait(timeout=STOP_TIMEOUT_S)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        self._log.close()
