"""schemathesis with ``--checks all`` against the real app: a live server on 127.0.0.1 on a free
port, started and ended by this test, a bounded number of examples per operation and a time cap.
Once for one lab's whole API, once for a class server's own routes with the instructor's token.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import pytest
from support.app import end, free_ports, instructor_token, wait_healthy

HERE = Path(__file__).resolve().parent
SCHEMATHESIS = Path(sys.executable).with_name("schemathesis")
READY_S = 30.0
RUN_CAP_S = 160  # schemathesis' own --max-time (50 s, a bound on the suite's time) is well below this
CLASS_CODE = "K7PX2M"  # the join example's code, so schemathesis' first join gets a world


@contextmanager
def live_server(workdir: Path, *args: str) -> Iterator[tuple[str, Path]]:
    """``python -m server *args`` on free ports; on the way out, its log must hold no bug."""
    port, zenoh_port = free_ports(2)
    url = f"http://127.0.0.1:{port}"
    log_path = workdir / "server.log"
    log = log_path.open("wb")
    proc = subprocess.Popen(
        [sys.executable, "-m", "server", "--port", str(port), "--zenoh-listen", f"tcp/127.0.0.1:{zenoh_port}",
         *args],
        cwd=workdir, stdout=log, stderr=subprocess.STDOUT,
    )  # fmt: skip
    try:
        wait_healthy(url, proc, READY_S, lambda: log_path.read_text()[-2000:])
        yield url, log_path
    finally:
        end(proc)
        log.close()
        # A node that a /api/run request names may fail to start (logged, and reported in the
        # answer); what must never appear is a bug: a traceback or the error net's entry.
        lines = log_path.read_text().splitlines()
        bugs = [i for i, line in enumerate(lines) if "unexpected error" in line or "Traceback" in line]
        # Show each bug with the lines that follow it, so a CI log names the failing frame.
        shown = "\n---\n".join("\n".join(lines[max(0, i - 2) : i + 25]) for i in bugs[:3])
        assert not bugs, f"the server logged {len(bugs)} bug(s) under schemathesis:\n{shown}"


def schemathesis(url: str, config: str, *extra: str) -> subprocess.CompletedProcess[str]:
    command = [
        str(SCHEMATHESIS), "--config-file", str(HERE / config), "--no-color",
        "run", f"{url}/openapi.json", "--checks", "all", "--max-examples", "20",
        "--max-time", str(RUN_CAP_S - 110), "--workers", "1", "--seed", "20",
        "--request-timeout", "10", *extra,
    ]  # fmt: skip
    return subprocess.run(
        command, capture_output=True, text=True, timeout=RUN_CAP_S, check=False,
        env={**os.environ, "SCHEMATHESIS_HOOKS": ""},
    )  # fmt: skip


@pytest.fixture(scope="module")
def live_url(tmp_path_factory: pytest.TempPathFactory) -> Iterator[str]:
    workdir = tmp_path_factory.mktemp("schemathesis_server")
    with live_server(workdir, "--launch", "rocket", "start_delay:=3600") as (url, _):
        yield url


def test_openapi_schemathesis_checks_all_pass(live_url: str) -> None:
    done = schemathesis(live_url, "schemathesis.toml")
    assert done.returncode == 0, done.stdout[-6000:] + done.stderr[-2000:]


def test_a_class_servers_own_routes_pass_checks_all_with_the_instructors_token(
    tmp_path_factory: pytest.TempPathFactory,
) -> None:
    """Joins (the first with the right code), the instructor's table, resets, kicks and
    broadcasts, fuzzed; ``ignored_auth`` also calls each secured route without the token."""
    workdir = tmp_path_factory.mktemp("schemathesis_class_server")
    with live_server(
        workdir, "--classroom", "--class-code", CLASS_CODE, "--max-worlds", "3", "--launch", "rocket",
        "start_delay:=3600",
    ) as (url, log_path):  # fmt: skip
        token = instructor_token(log_path.read_text())
        done = schemathesis(
            url, "schemathesis_classroom.toml", "--include-path-regex", "^/api/classroom/",
            "--header", f"Authorization: Bearer {token}",
        )  # fmt: skip
        assert done.returncode == 0, done.stdout[-6000:] + done.stderr[-2000:]
        # The run covered every route of the class server's own (the document lists 11).
        assert re.search(r"Selected:\s+11/\d+", done.stdout) and re.search(r"Tested:\s+11\b", done.stdout), (
            done.stdout
        )
