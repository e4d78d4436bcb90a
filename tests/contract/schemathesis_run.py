"""schemathesis with ``--checks all`` against the real app: a live server on 127.0.0.1 on free
ports, started and ended by the test, a bounded number of examples per operation and a time cap.
The lab's whole API (test_openapi_schemathesis.py) and a class server's own routes
(test_class_schemathesis.py) are two files, so pytest-xdist can run them side by side.
"""

from __future__ import annotations

import os
import subprocess
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from support.app import end, free_ports, wait_healthy
from support.forked_server import start_server

HERE = Path(__file__).resolve().parent
SCHEMATHESIS = Path(sys.executable).with_name("schemathesis")
READY_S = 90.0  # the app imports in 3 s when quiet; a loaded 2-core machine took over 30 s
# schemathesis' own --max-time is the run's budget, split between its four phases; it spends all
# of it (fuzzing and stateful testing draw new cases until it is spent: without it, at 20 examples
# an operation, a run took 4 min on a loaded machine). At 20 s the lab's run still tests all 49
# operations in every phase, the coverage phase's boundary cases whole: 1,661 cases, where 30 s
# drew 2,895 and 50 s 3,859 (2-vCPU AMD EPYC, 2026-11-30), and the suite's two runs give the rest
# of the gate 60 s of their cores. RUN_CAP_S bounds the process.
MAX_TIME_S = 20
RUN_CAP_S = MAX_TIME_S + 110


@contextmanager
def live_server(workdir: Path, *args: str) -> Iterator[tuple[str, Path]]:
    """``python -m server *args`` on free ports; on the way out, its log must hold no bug."""
    port, zenoh_port = free_ports(2)
    url = f"http://127.0.0.1:{port}"
    log_path = workdir / "server.log"
    proc = start_server(
        ["--port", str(port), "--zenoh-listen", f"tcp/127.0.0.1:{zenoh_port}", *args],
        cwd=workdir,
        log=log_path,
    )
    try:
        wait_healthy(url, proc, READY_S, lambda: log_path.read_text()[-2000:])
        yield url, log_path
    finally:
        end(proc)
        # A node that a /api/run request names may fail to start (logged, and reported in the
        # answer); what must never appear is a bug: a traceback or the error net's entry.
        lines = log_path.read_text().splitlines()
        bugs = [i for i, line in enumerate(lines) if "unexpected error" in line or "Traceback" in line]
        # Show each bug with the lines that follow it, so a CI log names the failing frame.
        shown = "\n---\n".join("\n".join(lines[max(0, i - 2) : i + 25]) for i in bugs[:3])
        assert not bugs, f"the server logged {len(bugs)} bug(s) under schemathesis:\n{shown}"


def schemathesis(url: str, config: str, *extra: str) -> subprocess.CompletedProcess[str]:
    command = [
        str(SCHEMATHESIS),
        "--config-file",
        str(HERE / config),
        "--no-color",
        "run",
        f"{url}/openapi.json",
        "--checks",
        "all",
        "--max-examples",
        "20",
        "--max-time",
        str(MAX_TIME_S),
        "--workers",
        "1",
        "--seed",
        "20",
        "--request-timeout",
        "10",
        *extra,
    ]
    return subprocess.run(
        command,
        capture_output=True,
        text=True,
        timeout=RUN_CAP_S,
        check=False,
        env={**os.environ, "SCHEMATHESIS_HOOKS": ""},
    )
