"""schemathesis with ``--checks all`` against the real app: a live server on 127.0.0.1 on a free
port, started and ended by this test, a bounded number of examples per operation and a time cap.
"""

from __future__ import annotations

import os
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest
from support.app import end, free_ports, wait_healthy

HERE = Path(__file__).resolve().parent
SCHEMATHESIS = Path(sys.executable).with_name("schemathesis")
READY_S = 30.0
RUN_CAP_S = 160  # schemathesis' own --max-time (50 s, a bound on the suite's time) is well below this


@pytest.fixture(scope="module")
def live_url(tmp_path_factory: pytest.TempPathFactory) -> Iterator[str]:
    workdir = tmp_path_factory.mktemp("schemathesis_server")
    port, zenoh_port = free_ports(2)
    url = f"http://127.0.0.1:{port}"
    log = (workdir / "server.log").open("wb")
    proc = subprocess.Popen(
        [sys.executable, "-m", "server", "--port", str(port), "--zenoh-listen", f"tcp/127.0.0.1:{zenoh_port}",
         "--launch", "rocket", "start_delay:=3600"],
        cwd=workdir, stdout=log, stderr=subprocess.STDOUT,
    )  # fmt: skip
    try:
        wait_healthy(url, proc, READY_S, lambda: (workdir / "server.log").read_text()[-2000:])
        yield url
    finally:
        end(proc)
        log.close()
        # A node that a /api/run request names may fail to start (logged, and reported in the
        # answer); what must never appear is a bug: a traceback or the error net's entry.
        text = (workdir / "server.log").read_text()
        lines = text.splitlines()
        bugs = [i for i, line in enumerate(lines) if "unexpected error" in line or "Traceback" in line]
        # Show each bug with the lines that follow it, so a CI log names the failing frame.
        shown = "\n---\n".join("\n".join(lines[max(0, i - 2) : i + 25]) for i in bugs[:3])
        assert not bugs, f"the server logged {len(bugs)} bug(s) under schemathesis:\n{shown}"


def test_openapi_schemathesis_checks_all_pass(live_url: str) -> None:
    command = [
        str(SCHEMATHESIS), "--config-file", str(HERE / "schemathesis.toml"), "--no-color",
        "run", f"{live_url}/openapi.json", "--checks", "all", "--max-examples", "20",
        "--max-time", str(RUN_CAP_S - 110), "--workers", "1", "--seed", "20",
        "--request-timeout", "10",
    ]  # fmt: skip
    done = subprocess.run(
        command, capture_output=True, text=True, timeout=RUN_CAP_S, check=False,
        env={**os.environ, "SCHEMATHESIS_HOOKS": ""},
    )  # fmt: skip
    assert done.returncode == 0, done.stdout[-6000:] + done.stderr[-2000:]
