"""A class server's cost against its number of worlds (issue 13).

For each size N: ``python -m server --classroom --launch fly`` in a child process, N students
joined through the REST API, one WebSocket per world echoing its drone's pose at 30 Hz (as the
page's pose stream would), then over a measuring window: the server's CPU (share of one core,
from /proc), its RSS, the pose frames each client got, and each world's sim tick lateness (p99
of the dynamics node's 100 Hz timer, from /api/nodes). Prints a table and writes
bench/results/classroom_worlds.json.

    python bench/classroom_worlds.py                 # sizes 1 5 10 30 60
    python bench/classroom_worlds.py --sizes 1 5 --window 10
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

import httpx

sys.path.insert(0, str(Path(__file__).resolve().parent))
from live_server import FrameReader, LiveServer
from machine import machine_info, save_results

CODE = "BENCH1"
POSE_THROTTLE_MS = 33  # ~30 Hz, the page's pose stream
WARM_S = 5.0
DYNAMICS = "flightgoggles_uav_dynamics"


def cpu_s(pid: int) -> float:
    """utime + stime of the process so far, in s."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def measure(size: int, window_s: float, extra: list[str]) -> dict[str, Any]:
    with tempfile.TemporaryDirectory() as tmp:
        args = ["--classroom", "--class-code", CODE, "--max-worlds", str(max(size, 1)), *extra]
        server = LiveServer(Path(tmp), "fly", *args)
        readers: list[FrameReader] = []
        try:
            tokens = []
            for i in range(size):
                reply = httpx.post(
                    f"{server.url}/api/classroom/join",
                    json={"name": f"student {i}", "code": CODE},
                    timeout=30,
                )
                reply.raise_for_status()
                tokens.append(reply.json()["token"])
            for token in tokens:
                url = f"{server.ws_url}/ws/topics/uav/sensors/gps?throttle_rate={POSE_THROTTLE_MS}"
                readers.append(FrameReader(url, {"Authorization": f"Bearer {token}"}))
            time.sleep(WARM_S)
            counts = [r.count() for r in readers]
            cpu0, t0 = cpu_s(server.proc.pid), time.monotonic()
            time.sleep(window_s)
            cpu1, t1 = cpu_s(server.proc.pid), time.monotonic()
            rates = [(r.count() - c) / (t1 - t0) for r, c in zip(readers, counts, strict=True)]
            lateness = []
            for token in tokens:
                info = httpx.get(
                    f"{server.url}/api/nodes/{DYNAMICS}",
                    headers={"Authorization": f"Bearer {token}"},
                    timeout=10,
                ).json()
                lateness.append(info["timers"][0]["lateness_p99_ms"])
            rss = server.rss_mib()
            problems = server.log_problems()
        finally:
            for r in readers:
                r.close()
            server.stop()
    return {
        "worlds": size,
        "cpu_core_share": round((cpu1 - cpu0) / (t1 - t0), 3),
        "rss_mib": round(rss, 1),
        "pose_hz_median": round(statistics.median(rates), 1) if rates else None,
        "pose_hz_min": round(min(rates), 1) if rates else None,
        "tick_lateness_p99_ms_median": round(statistics.median(lateness), 2) if lateness else None,
        "tick_lateness_p99_ms_max": round(max(lateness), 2) if lateness else None,
        "log_problems": problems[:5],
    }


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--sizes", type=int, nargs="+", default=[1, 5, 10, 30, 60])
    parser.add_argument("--window", type=float, default=20.0, help="measuring window per size, s")
    parser.add_argument("--no-zenoh", action="store_true", help="worlds in-process only (no Zenoh sessions)")
    args = parser.parse_args()
    info = machine_info()
    print(f"machine: {info['cpu_model']}, {info['nproc']} CPUs, Python {info['python']}", flush=True)
    print(
        f"{'worlds':>6} {'CPU (core)':>10} {'RSS MiB':>8} {'pose Hz med/min':>16} {'tick p99 ms med/max':>20}"
    )
    rows = []
    for size in args.sizes:
        row = measure(size, args.window, ["--no-zenoh"] if args.no_zenoh else [])
        rows.append(row)
        print(f"{row['worlds']:>6} {row['cpu_core_share']:>10.2f} {row['rss_mib']:>8.0f} "
              f"{row['pose_hz_median']!s:>8}/{row['pose_hz_min']!s:<7} "
              f"{row['tick_lateness_p99_ms_median']!s:>9}/{row['tick_lateness_p99_ms_max']!s:<9}", flush=True)  # fmt: skip
        if row["log_problems"]:
            print("   server log:", row["log_problems"], flush=True)
    name = "classroom_worlds_no_zenoh" if args.no_zenoh else "classroom_worlds"
    save_results(name, {"machine": info, "window_s": args.window, "zenoh": not args.no_zenoh, "rows": rows})


if __name__ == "__main__":
    main()
