"""Bench: a soak of the full lab under steady use: does memory drift, do the sims fall behind,
does anything go wrong in the log?

    .venv/bin/python bench/soak.py [--duration-s 1800] [--window-s 300] [--echo-clients 20]

``python -m server --launch all`` (the rocket and the quadrotor, viser on, no browser) runs as a
child process on a free loopback port, with, for ``--duration-s``:

* ``--echo-clients`` WebSocket echo clients reading as fast as frames come, spread over the
  drone's and the rocket's topics (/uav/sensors/gps, /uav/sensors/velocity, /uav/sensors/attitude,
  /sensor_vel, /countdown, /rosout);
* one stalled client: an echo of /uav/sensors/gps that never reads (the server must drop the
  oldest frames for it, not grow);
* a REST publisher: ``POST /api/publish`` of a position setpoint at 10 Hz, moving the drone
  between two points every 10 s.

Every ``--sample-s`` the bench reads VmRSS and, from ``GET /api/nodes/flightgoggles_uav_dynamics``,
the p99 lateness of the sim's tick timer over its last 2000 ticks (20 s at 100 Hz; the window the
server keeps). Reported per ``--window-s`` window: the median and the largest of those p99
samples, and RSS at the window's end. RSS drift is the last sample minus the first one taken
after ``--settle-s``. Errors: lines of the server's log with ERROR, a traceback or an exception,
and any request that failed. Results are printed with the machine's details and written to
bench/results/soak.json.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import json
import statistics
import sys
import tempfile
import time
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import httpx
import websockets

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from live_server import LiveServer
from machine import machine_info

RESULTS = Path(__file__).resolve().parent / "results"
ECHO_TOPICS = (
    "uav/sensors/gps",
    "uav/sensors/velocity",
    "uav/sensors/attitude",
    "sensor_vel",
    "countdown",
    "rosout",
)
SIM_NODE = "flightgoggles_uav_dynamics"
SETPOINTS = ({"x": 2.0, "y": 2.0, "z": 4.0}, {"x": -2.0, "y": -1.0, "z": 3.0})


class Soak:
    def __init__(self, server: LiveServer, args: argparse.Namespace) -> None:
        self.server, self.args = server, args
        self.frames = 0
        self.failures: list[str] = []
        self.samples: list[dict[str, float | None]] = []
        self.published = 0
        self.t0 = time.monotonic()

    def elapsed(self) -> float:
        return time.monotonic() - self.t0

    async def echo(self, topic: str, end_s: float) -> None:
        try:
            async with websockets.connect(f"{self.server.ws_url}/ws/topics/{topic}") as ws:
                while self.elapsed() < end_s:
                    with contextlib.suppress(TimeoutError):
                        async with asyncio.timeout(1.0):
                            await ws.recv()
                            self.frames += 1
        except (OSError, websockets.exceptions.WebSocketException) as exc:
            self.failures.append(f"echo {topic}: {type(exc).__name__}: {exc}")

    async def stalled(self, end_s: float) -> None:
        async with websockets.connect(f"{self.server.ws_url}/ws/topics/uav/sensors/gps", max_queue=1):
            await asyncio.sleep(max(0.0, end_s - self.elapsed()))  # connected, never reads

    async def publisher(self, http: httpx.AsyncClient, end_s: float) -> None:
        period_s = 0.1
        next_s = self.elapsed()
        while self.elapsed() < end_s:
            setpoint = SETPOINTS[int(self.elapsed() // 10) % 2]
            body = {"topic": "/uav/input/position", "msg": setpoint}
            try:
                response = await http.post("/api/publish", json=body)
                if response.status_code != 200:
                    self.failures.append(f"publish: HTTP {response.status_code}: {response.text[:200]}")
                self.published += 1
            except httpx.HTTPError as exc:
                self.failures.append(f"publish: {type(exc).__name__}: {exc}")
            next_s += period_s
            await asyncio.sleep(max(0.0, next_s - self.elapsed()))

    async def sampler(self, http: httpx.AsyncClient, end_s: float) -> None:
        while self.elapsed() < end_s:
            await asyncio.sleep(self.args.sample_s)
            p99: float | None = None
            try:
                info = (await http.get(f"/api/nodes/{SIM_NODE}")).json()
                p99 = max((t["lateness_p99_ms"] or 0.0) for t in info["timers"]) if info["timers"] else None
            except (httpx.HTTPError, KeyError, ValueError) as exc:
                self.failures.append(f"sample: {type(exc).__name__}: {exc}")
            self.samples.append({"t_s": self.elapsed(), "rss_mib": self.server.rss_mib(), "sim_p99_ms": p99})

    async def run(self) -> None:
        end_s = self.args.duration_s
        async with httpx.AsyncClient(base_url=self.server.url, timeout=10) as http:
            tasks = [
                self.echo(ECHO_TOPICS[i % len(ECHO_TOPICS)], end_s) for i in range(self.args.echo_clients)
            ]
            tasks += [self.stalled(end_s), self.publisher(http, end_s), self.sampler(http, end_s)]
            await asyncio.gather(*tasks)


def windows(samples: list[dict[str, Any]], window_s: float) -> list[dict[str, Any]]:
    out = []
    count = int(max(s["t_s"] for s in samples) // window_s) + 1
    for w in range(count):
        inside = [s for s in samples if w * window_s <= s["t_s"] < (w + 1) * window_s]
        p99s = [s["sim_p99_ms"] for s in inside if s["sim_p99_ms"] is not None]
        if inside:
            out.append(
                {
                    "window": f"{w * window_s / 60:g}-{(w + 1) * window_s / 60:g} min",
                    "sim_p99_ms_median": statistics.median(p99s) if p99s else None,
                    "sim_p99_ms_max": max(p99s) if p99s else None,
                    "rss_mib_end": inside[-1]["rss_mib"],
                }
            )
    return out


def main() -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--duration-s", type=float, default=1800.0)
    parser.add_argument("--window-s", type=float, default=300.0)
    parser.add_argument("--sample-s", type=float, default=15.0)
    parser.add_argument("--settle-s", type=float, default=60.0, help="RSS drift is measured from here")
    parser.add_argument("--echo-clients", type=int, default=20)
    args = parser.parse_args()
    machine = machine_info()
    with tempfile.TemporaryDirectory(prefix="bench_soak_") as workdir:
        server = LiveServer(Path(workdir), "all")
        try:
            soak = Soak(server, args)
            asyncio.run(soak.run())
            problems = server.log_problems()
        finally:
            server.stop()
    settled = [s for s in soak.samples if s["t_s"] >= args.settle_s] or soak.samples
    summary = {
        "duration_s": args.duration_s,
        "rss_settled_mib": settled[0]["rss_mib"],
        "rss_last_mib": settled[-1]["rss_mib"],
        "rss_drift_mib": settled[-1]["rss_mib"] - settled[0]["rss_mib"],
        "frames_received": soak.frames,
        "setpoints_published": soak.published,
        "request_failures": len(soak.failures),
        "log_problems": len(problems),
        "windows": windows(soak.samples, args.window_s),
    }
    print(
        f"machine: {machine['cpu_model']} x{machine['nproc']}, Python {machine['python']}, "
        f"load at start {machine['load_average_at_start']} (shared machine: figures are noisy)"
    )
    print(json.dumps(summary, indent=2))
    for line in (problems + soak.failures)[:20]:
        print("problem:", line)
    RESULTS.mkdir(exist_ok=True)
    out = {
        "when": datetime.now(UTC).isoformat(),
        "machine": machine,
        "args": vars(args),
        "summary": summary,
        "samples": soak.samples,
        "log_problems": problems[:100],
        "failures": soak.failures[:100],
    }
    (RESULTS / "soak.json").write_text(json.dumps(out, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
