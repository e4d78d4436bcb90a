"""A class server's cost against its number of worlds.

For each size N: ``python -m server --classroom --launch fly`` in a child process, N students
joined through the REST API, one WebSocket per world echoing its drone's pose at 30 Hz (as the
page's pose stream would), then over a measuring window: the server's CPU (share of one core,
from /proc), its RSS, the pose frames each client got, and each world's sim tick lateness (p99
of the dynamics node's 100 Hz timer, from /api/nodes) and the rate that timer kept (its calls over
the window). Prints a table and writes bench/results/classroom_worlds.json.

    python bench/classroom_worlds.py                 # sizes 1 5 10 30 60
    python bench/classroom_worlds.py --sizes 1 5 --window 10
    python bench/classroom_worlds.py --sizes 30 --workers 1 --local-worlds 15   # half on a worker
    python bench/classroom_worlds.py --sizes 30 --no-clients                    # no pose stream
    python bench/classroom_worlds.py --sizes 10 --page-clients   # a page-like client per student

With ``--page-clients`` each student's client is bench/page_client.py instead of a lone pose
stream: viser's WebSocket, the HUD's pose stream and the key channel's heartbeat, as an open lab
page; each row then has every channel's median rate over the clients (``page_hz``).
"""

from __future__ import annotations

import argparse
import os
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

import httpx

sys.path.insert(0, str(Path(__file__).resolve().parent))
from live_server import READER, FrameReader, LiveServer, class_join, cpu_s, rss_mib
from machine import machine_info, save_results
from page_client import PageClient, PageClients, median_rates

CODE = "BENCH1"
POSE_THROTTLE_MS = 33  # ~30 Hz, the page's pose stream
ADMIT_WAIT_S = 60.0  # how long a queued join is polled before the bench goes on without it
WARM_S = 5.0
DYNAMICS = "flightgoggles_uav_dynamics"


def start_workers(
    server: LiveServer, count: int, per_worker: int, workdir: Path
) -> list[subprocess.Popen[bytes]]:
    """``count`` world workers on the class server's router, each for up to ``per_worker`` worlds."""
    token = server.instructor_token()
    env = {**os.environ, "ROS2LAB_TOKEN": token, "PYTHONPATH": str(Path(__file__).resolve().parent.parent)}
    procs = [
        subprocess.Popen(
            [
                sys.executable,
                "-m",
                "server",
                "world-worker",
                "--connect",
                f"tcp/127.0.0.1:{server.zenoh_port}",
                "--id",
                f"w{i}",
                "--max-worlds",
                str(per_worker),
            ],
            cwd=workdir,
            env=env,
            stdout=(workdir / f"w{i}.log").open("wb"),
            stderr=subprocess.STDOUT,
        )
        for i in range(count)
    ]
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        listed = httpx.get(
            f"{server.url}/api/classroom/workers", headers={"Authorization": f"Bearer {token}"}, timeout=10
        )
        if len(listed.json()["workers"]) == count:
            return procs
        time.sleep(0.2)
    raise RuntimeError("the workers did not show up on the class server's router")


def dynamics_timer(server: LiveServer, token: str) -> dict[str, Any]:
    """The world's dynamics node's 100 Hz timer, as /api/nodes shows it (calls, lateness)."""
    info = READER.get(
        f"{server.url}/api/nodes/{DYNAMICS}", headers={"Authorization": f"Bearer {token}"}
    ).json()
    timer: dict[str, Any] = info["timers"][0]
    return timer


def join(url: str, name: str) -> str | None:
    """The new world's token; a join the class server queues at its capacity (202) is polled
    until it is admitted, or None when it is refused or still waits after ADMIT_WAIT_S."""
    reply = class_join(url, name, CODE, ADMIT_WAIT_S)
    if reply.status_code == 201:
        return str(reply.json()["token"])
    if reply.status_code in (202, 503):
        return None
    reply.raise_for_status()
    raise RuntimeError(f"join answered {reply.status_code}: {reply.text}")


def measure(
    size: int,
    window_s: float,
    extra: list[str],
    workers: int = 0,
    local_worlds: int = 0,
    clients: bool = True,
    page_clients: bool = False,
) -> dict[str, Any]:
    with tempfile.TemporaryDirectory() as tmp:
        # The bench places its own workers (none by default): the server starts none itself.
        args = [
            "--classroom",
            "--class-code",
            CODE,
            "--max-worlds",
            str(max(size, 1)),
            "--workers",
            "0",
            *extra,
        ]
        if workers:
            args += ["--local-worlds", str(local_worlds)]
        server = LiveServer(Path(tmp), "fly", *args)
        readers: list[FrameReader] = []
        worker_procs: list[subprocess.Popen[bytes]] = []
        try:
            if workers:
                worker_procs = start_workers(server, workers, -(-(size - local_worlds) // workers), Path(tmp))
            pids = [server.proc.pid, *(p.pid for p in worker_procs)]
            tokens = []
            for i in range(size):
                token = join(server.url, f"student {i}")
                if token is None:
                    print(
                        f"  join {i + 1} of {size} was not admitted within {ADMIT_WAIT_S:.0f} s "
                        "(the class server's capacity): measured with the worlds admitted",
                        flush=True,
                    )
                    break
                tokens.append(token)
            pages = PageClients([PageClient(server.url, t) for t in tokens], window_s, WARM_S)
            if page_clients:
                pages.start()
            for token in tokens if clients and not page_clients else ():
                url = f"{server.ws_url}/ws/topics/uav/sensors/gps?throttle_rate={POSE_THROTTLE_MS}"
                readers.append(FrameReader(url, {"Authorization": f"Bearer {token}"}))
            time.sleep(WARM_S)
            # Each world's timer calls with the time they were read: the reads take a while under
            # load, so each world's rate is over its own interval, not the CPU window's.
            calls0 = [(dynamics_timer(server, token)["calls"], time.monotonic()) for token in tokens]
            counts = [r.count() for r in readers]
            cpu0, t0 = sum(cpu_s(p) for p in pids), time.monotonic()
            time.sleep(window_s)
            cpu1, t1 = sum(cpu_s(p) for p in pids), time.monotonic()
            rates = [(r.count() - c) / (t1 - t0) for r, c in zip(readers, counts, strict=True)]
            timers = [(dynamics_timer(server, token), time.monotonic()) for token in tokens]
            dynamics_hz = [
                (t["calls"] - c) / (at - since) for (t, at), (c, since) in zip(timers, calls0, strict=True)
            ]
            lateness = [t["lateness_p99_ms"] for t, _ in timers]
            rss = server.rss_mib() + sum(rss_mib(p.pid) for p in worker_procs)
            page_rates, page_errors = pages.results(WARM_S + window_s + 60) if page_clients else ([], [])
            problems = server.log_problems()
        finally:
            for r in readers:
                r.close()
            for proc in worker_procs:
                proc.send_signal(signal.SIGINT)
            for proc in worker_procs:
                try:
                    proc.wait(timeout=15)
                except subprocess.TimeoutExpired:
                    proc.kill()
                    proc.wait(timeout=15)
            server.stop()
    return {
        "worlds": len(tokens),
        "asked": size,
        "workers": workers,
        "local_worlds": local_worlds if workers else size,
        "cpu_core_share": round((cpu1 - cpu0) / (t1 - t0), 3),
        "rss_mib": round(rss, 1),
        "pose_hz_median": round(statistics.median(rates), 1) if rates else None,
        "pose_hz_min": round(min(rates), 1) if rates else None,
        "dynamics_hz_median": round(statistics.median(dynamics_hz), 1) if dynamics_hz else None,
        "dynamics_hz_min": round(min(dynamics_hz), 1) if dynamics_hz else None,
        "tick_lateness_p99_ms_median": round(statistics.median(lateness), 2) if lateness else None,
        "tick_lateness_p99_ms_max": round(max(lateness), 2) if lateness else None,
        "page_hz": median_rates(page_rates) if page_clients else None,
        "page_errors": page_errors[:5],
        "log_problems": problems[:5],
    }


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--sizes", type=int, nargs="+", default=[1, 5, 10, 30, 60])
    parser.add_argument("--window", type=float, default=20.0, help="measuring window per size, s")
    parser.add_argument("--no-zenoh", action="store_true", help="worlds in-process only (no Zenoh sessions)")
    parser.add_argument("--no-clients", action="store_true", help="no pose stream: the worlds alone")
    parser.add_argument(
        "--page-clients",
        action="store_true",
        help="a page-like client per student (bench/page_client.py) instead of a lone pose stream",
    )
    parser.add_argument(
        "--workers",
        type=int,
        default=0,
        help=(
            "worlds on this many world workers (ros2lab world-worker) instead of the class server; "
            "CPU and RSS are then the sum over the server and its workers"
        ),
    )
    parser.add_argument(
        "--local-worlds",
        type=int,
        default=0,
        help="with --workers: this many worlds stay on the class server, the rest go to the workers",
    )
    args = parser.parse_args()
    info = machine_info()
    print(f"machine: {info['cpu_model']}, {info['nproc']} CPUs, Python {info['python']}", flush=True)
    print(
        f"{'worlds':>6} {'CPU (core)':>10} {'RSS MiB':>8} {'pose Hz med/min':>16} {'tick p99 ms med/max':>20}"
        f" {'dynamics Hz med/min':>20}"
    )
    rows = []
    for size in args.sizes:
        row = measure(
            size,
            args.window,
            ["--no-zenoh"] if args.no_zenoh else [],
            args.workers,
            args.local_worlds,
            clients=not args.no_clients,
            page_clients=args.page_clients,
        )
        rows.append(row)
        print(
            f"{row['worlds']:>6} {row['cpu_core_share']:>10.2f} {row['rss_mib']:>8.0f} "
            f"{row['pose_hz_median']!s:>8}/{row['pose_hz_min']!s:<7} "
            f"{row['tick_lateness_p99_ms_median']!s:>9}/{row['tick_lateness_p99_ms_max']!s:<9} "
            f"{row['dynamics_hz_median']!s:>9}/{row['dynamics_hz_min']!s:<9}",
            flush=True,
        )
        if row["page_hz"] is not None:
            print(
                "   page clients, median Hz per channel:",
                row["page_hz"],
                row["page_errors"] or "",
                flush=True,
            )
        if row["log_problems"]:
            print("   server log:", row["log_problems"], flush=True)
    if args.workers and args.no_zenoh:
        parser.error("world workers join the class server's Zenoh router: drop --no-zenoh")
    name = "classroom_worlds_no_zenoh" if args.no_zenoh else "classroom_worlds"
    name += f"_{args.workers}_workers" if args.workers else ""
    name += f"_{args.local_worlds}_local" if args.workers and args.local_worlds else ""
    name += "_no_clients" if args.no_clients else ""
    name += "_page_clients" if args.page_clients else ""
    save_results(
        name,
        {
            "machine": info,
            "window_s": args.window,
            "zenoh": not args.no_zenoh,
            "workers": args.workers,
            "local_worlds": args.local_worlds,
            "pose_clients": not args.no_clients,
            "page_clients": args.page_clients,
            "rows": rows,
        },
    )


if __name__ == "__main__":
    main()
