"""A test server's start two ways, alternating: ``python -m server`` in a fresh interpreter, and
forked from the tests' starter (tests/support/forked_server.py), which has imported the app once.
For each: the time from asking to ``/api/health`` answering, and the server process's CPU by then
(from ``/proc``); medians over ``--starts`` of each, with the starter's own one-off import beside
them. Each server is ended by Ctrl-C to its own id.

    env -u PYTHONDONTWRITEBYTECODE PYTHONPYCACHEPREFIX=$PWD/.venv/pycache \
        .venv/bin/python bench/server_start.py --starts 7

(with the bytecode where scripts/check keeps it, as the suite's servers find it).
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

from machine import machine_info, save_results

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "tests"))

from support.app import end, free_ports, healthy
from support.forked_server import Starter, start_server

TICK_S = 1.0 / os.sysconf("SC_CLK_TCK")


def cpu_s(pid: int) -> float:
    text = Path(f"/proc/{pid}/stat").read_text()
    fields = text[text.rindex(")") + 2 :].split()
    return (int(fields[11]) + int(fields[12])) * TICK_S


def one_start(way: str, starter: Starter, launch: str, workdir: Path) -> tuple[float, float]:
    """(seconds to /api/health, the server's CPU seconds by then)."""
    port, zenoh_port = free_ports(2)
    args = [
        "--host",
        "127.0.0.1",
        "--port",
        str(port),
        "--zenoh-listen",
        f"tcp/127.0.0.1:{zenoh_port}",
        "--state-dir",
        str(workdir / "state"),
        "--launch",
        launch,
        "--no-foxglove",
    ]
    log = workdir / f"{way}-{port}.log"
    began = time.monotonic()
    if way == "forked":
        proc = starter.start(args, workdir, log, dict(os.environ))
    else:
        proc = start_server(args, cwd=workdir, log=log)  # TELEOP_TEST_FORK=0: a fresh interpreter
    try:
        while not healthy(f"http://127.0.0.1:{port}"):
            if proc.poll() is not None:
                raise SystemExit(f"the server ended (code {proc.returncode}):\n{log.read_text()[-2000:]}")
            time.sleep(0.02)
        return time.monotonic() - began, cpu_s(proc.pid)
    finally:
        end(proc)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--starts", type=int, default=5, help="starts of each way (default 5)")
    parser.add_argument("--launch", default="fly", help="the launch the servers run (default fly)")
    options = parser.parse_args()
    info = machine_info()
    print(f"machine: {info['cpu_model']}, {info['nproc']} CPUs, Python {info['python']}", flush=True)
    os.environ["TELEOP_TEST_FORK"] = "0"  # start_server's own way: python -m server
    began = time.monotonic()
    starter = Starter()
    starter_s = time.monotonic() - began
    results: dict[str, list[tuple[float, float]]] = {"exec": [], "forked": []}
    with tempfile.TemporaryDirectory(prefix="server-start-") as tmp:
        try:
            for i in range(options.starts):
                for way in ("exec", "forked") if i % 2 == 0 else ("forked", "exec"):
                    results[way].append(one_start(way, starter, options.launch, Path(tmp)))
        finally:
            starter.close()
    summary = {
        way: {
            "health_s": statistics.median(t for t, _ in runs),
            "cpu_s": statistics.median(c for _, c in runs),
        }
        for way, runs in results.items()
    }
    print(f"the starter's imports: {starter_s:.2f} s, once per test process")
    for way, figures in summary.items():
        print(
            f"{way:7} to /api/health {figures['health_s']:.2f} s, CPU {figures['cpu_s']:.2f} s "
            f"(median of {options.starts})"
        )
    ratio = summary["exec"]["cpu_s"] / max(summary["forked"]["cpu_s"], 1e-9)
    print(f"CPU per start, exec / forked: {ratio:.1f}x")
    save_results(
        "server_start",
        {
            "machine": info,
            "launch": options.launch,
            "starts": options.starts,
            "starter_s": starter_s,
            "summary": summary,
            "runs": results,
        },
    )


if __name__ == "__main__":
    main()
