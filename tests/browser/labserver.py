"""For the browser tests: find Debian's Chromium, and run a real lab server in a subprocess.

Without a Chromium the tests are skipped, except in CI (CI=true), where a browser test that
does not run is a failure.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest
from support.app import end, free_ports, own_state, wait_healthy
from support.forked_server import start_server

REPO = Path(__file__).resolve().parents[2]
CHROMIUM_ARGS = [
    "--headless=new",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
    "--disable-quic",
    "--use-angle=swiftshader",
    "--enable-unsafe-swiftshader",
]
# About 3 s when quiet; on a loaded 2-core machine, with a page drawing in software, over 30 s.
SERVER_READY_S = 90.0
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


class LabServer:
    """``python -m server`` in a subprocess on a free loopback port."""

    def __init__(self, launch_args: list[str], log_path: Path) -> None:
        self.port, self.zenoh_port = free_ports(2)  # the Zenoh router on loopback, never 7447
        self.url = f"http://127.0.0.1:{self.port}"
        self.log_path = log_path
        self._log = log_path.open("w")
        self.proc = start_server(
            [
                "--host",
                "127.0.0.1",
                "--port",
                str(self.port),
                "--zenoh-listen",
                f"tcp/127.0.0.1:{self.zenoh_port}",
                *own_state(log_path.parent, launch_args),
                *launch_args,
            ],
            cwd=REPO,
            log=log_path,
        )

    def wait_ready(self, timeout_s: float = SERVER_READY_S) -> None:
        wait_healthy(self.url, self.proc, timeout_s, self.log_tail)

    def stop(self) -> None:
        """Ctrl-C, as a person would; killed if it does not stop in time."""
        end(self.proc, SERVER_STOP_S)
        self._log.close()

    def log_tail(self, chars: int = 3000) -> str:
        self._log.flush()
        return self.log_path.read_text(errors="replace")[-chars:]
