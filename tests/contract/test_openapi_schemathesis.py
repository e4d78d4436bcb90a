"""schemathesis with ``--checks all`` against the real app: a live server on 127.0.0.1 on a free
port, started and ended by this test, a bounded number of examples per operation and a time cap.
"""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import httpx
import pytest

HERE = Path(__file__).resolve().parent
SCHEMATHESIS = Path(sys.executable).with_name("schemathesis")
READY_S = 30.0
RUN_CAP_S = 240  # schemathesis' own --max-time is below this


def _free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


@pytest.fixture(scope="module")
def live_url(tmp_path_factory: pytest.TempPathFactory) -> Iterator[str]:
    workdir = tmp_path_factory.mktemp("schemathesis_server")
    port = _free_port()
    url = f"http://127.0.0.1:{port}"
    log = (workdir / "server.log").open("wb")
    proc = subprocess.Popen(
        [sys.executable, "-m", "server", "--port", str(port), "--launch", "rocket", "start_delay:=3600"],
        cwd=workdir, stdout=log, stderr=subprocess.STDOUT,
    )  # fmt: skip
    try:
        deadline = time.monotonic() + READY_S
        while True:
            try:
                if httpx.get(f"{url}/api/health", timeout=1.0).status_code == 200:
                    break
            except httpx.HTTPError:
                pass
            if proc.poll() is not None or time.monotonic() > deadline:
                pytest.fail(f"the server did not come up: {(workdir / 'server.log').read_text()[-2000:]}")
            time.sleep(0.1)
        yield url
    finally:
        proc.send_signal(signal.SIGINT)
        try:
            proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
        log.close()
        errors = [line for line in (workdir / "server.log").read_text().splitlines() if " ERROR " in line]
        assert not errors, f"the server logged errors under schemathesis: {errors[:5]}"


def test_openapi_schemathesis_checks_all_pass(live_url: str) -> None:
    command = [
        str(SCHEMATHESIS), "--config-file", str(HERE / "schemathesis.toml"), "--no-color",
        "run", f"{live_url}/openapi.json", "--checks", "all", "--max-examples", "25",
        "--max-time", str(RUN_CAP_S - 60), "--workers", "1", "--seed", "20",
        "--request-timeout", "10",
    ]  # fmt: skip
    done = subprocess.run(
        command, capture_output=True, text=True, timeout=RUN_CAP_S, check=False,
        env={**os.environ, "SCHEMATHESIS_HOOKS": ""},
    )  # fmt: skip
    assert done.returncode == 0, done.stdout[-6000:] + done.stderr[-2000:]
