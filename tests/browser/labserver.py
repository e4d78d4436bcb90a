"""For the browser tests: find Debian's Chromium, and run a real lab server in a subprocess.

Without a Chromium the tests are skipped, except in CI (CI=true), where a browser test that
does not run is a failure.
"""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import httpx
import pytest
from support.app import free_port

REPO = Path(__file__).resolve().parents[2]
CHROMIUM_ARGS = [
    "--headless=new", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
    "--disable-component-update", "--disable-sync", "--no-first-run", "--disable-quic",
    "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
]  # fmt: skip
SERVER_READY_S = 30.0
SERVER_STOP_S = 10.0


def find_chromium() -> str:
    """The Chromium to drive; skips the test when there is none, fails it in CI."""
    path = shutil.which("chromium") or ("/usr/bin/chromium" if Path("/usr/bin/chromium").is_file() else None)
    if path is None:
        message = "no Chromium found (shutil.which('chromium'), /usr/bin/chromium): apt-get install chromium"
        if os.environ.get("CI") == "true":
            pytest.fail(f"{message}; in CI the browser tests must run")
        pytest.skip(message)
    return path


def healthy(url: str) -> bool:
    try:
        return httpx.get(f"{url}/api/health", timeout=1.0).status_code == 200
    except httpx.HTTPError:
        return False


class LabServer:
    """``python -m server`` in a subprocess on a free loopback port."""

    def __init__(self, launch_args: list[str], log_path: Path) -> None:
        self.port = free_port()
        self.url = f"http://127.0.0.1:{self.port}"
        self.log_path = log_path
        self._log = log_path.open("w")
        self.zenoh_port = free_port()  # the app's Zenoh router, on loopback, never the shared 7447
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "server", "--host", "127.0.0.1", "--port", str(self.port),
             "--zenoh-listen", f"tcp/127.0.0.1:{self.zenoh_port}", *launch_args],
            cwd=REPO, stdout=self._log, stderr=subprocess.STDOUT,
        )  # fmt: skip

    def wait_ready(self, timeout_s: float = SERVER_READY_S) -> None:
        deadline = time.monotonic() + timeout_s
        while not healthy(self.url):
            if self.proc.poll() is not None or time.monotonic() > deadline:
                pytest.fail(f"the server did not come up within {timeout_s} s:\n{self.log_tail()}")
            time.sleep(0.1)

    def stop(self) -> None:
        """Ctrl-C, as a person would; killed if it does not stop in time."""
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGINT)
            try:
                self.proc.wait(timeout=SERVER_STOP_S)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait(timeout=SERVER_STOP_S)
        self._log.close()

    def log_tail(self, chars: int = 3000) -> str:
        self._log.flush()
        return self.log_path.read_text(errors="replace")[-chars:]
