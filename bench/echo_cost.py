"""What a topic echo costs the lab that serves it: the page's pose stream, as many clients at once.

    .venv/bin/python bench/echo_cost.py                    # 20 clients, 3 rounds of 15 s a kind
    .venv/bin/python bench/echo_cost.py --clients 10 --rounds 2 --window 10

One ``python -m server --launch fly`` in a child process; N WebSocket clients on
``/ws/topics/uav/sensors/gps`` (the drone's 100 Hz pose) as the page's pose worker asks for it
(``throttle_rate=20``: the newest pose every 20 ms), each offering ``permessage-deflate`` as a
browser does, then the same with every pose (``queue_length=10``) and ``throttle_rate=33``, and
none at all (the lab alone). The kinds take turns, round after
round, so a machine that slows down slows them alike. For each window: the server's CPU (share of
one core, from /proc) and the frames each client got a second. Printed as the CPU of one client
above the lab alone, in ms a second (the median over the rounds), and written to
bench/results/echo_cost.json.
"""

from __future__ import annotations

import argparse
import asyncio
import statistics
import tempfile
import time
from pathlib import Path

import websockets
from live_server import LiveServer, cpu_s
from machine import machine_info, save_results

TOPIC = "uav/sensors/gps"
KINDS = {
    "alone": None,
    "throttle 20 ms (the page)": "throttle_rate=20",
    "every pose": "queue_length=10",
    "throttle 33 ms": "throttle_rate=33",
}


async def _clients(url: str, count: int, window_s: float) -> int:
    """``count`` clients reading ``url`` for ``window_s``; the frames they got in all."""
    got = [0]

    async def one() -> None:
        async with websockets.connect(url, compression="deflate", max_size=None) as ws:
            while True:
                await ws.recv()
                got[0] += 1

    tasks = [asyncio.create_task(one()) for _ in range(count)]
    await asyncio.sleep(window_s)
    for task in tasks:
        task.cancel()
    await asyncio.gather(*tasks, return_exceptions=True)
    return got[0]


def measure(server: LiveServer, query: str | None, clients: int, window_s: float) -> tuple[float, float]:
    """(the server's CPU share over the window, frames a client got a second)."""
    before, start = cpu_s(server.proc.pid), time.monotonic()
    if query is None:
        time.sleep(window_s)
        frames = 0
    else:
        frames = asyncio.run(_clients(f"{server.ws_url}/ws/topics/{TOPIC}?{query}", clients, window_s))
    elapsed = time.monotonic() - start
    return (cpu_s(server.proc.pid) - before) / elapsed, frames / elapsed / clients


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--clients", type=int, default=20)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--window", type=float, default=15.0, help="seconds a kind is measured, each round")
    parser.add_argument(
        "--warm", type=float, default=5.0, help="seconds after the lab is up, before the first"
    )
    args = parser.parse_args()
    machine = machine_info()
    print(f"machine: {machine['cpu_model']}, {machine['nproc']} CPUs, Python {machine['python']}", flush=True)
    readings: dict[str, list[tuple[float, float]]] = {kind: [] for kind in KINDS}
    with tempfile.TemporaryDirectory() as workdir:
        server = LiveServer(Path(workdir), "fly")
        try:
            time.sleep(args.warm)
            for round_ in range(args.rounds):
                for kind, query in KINDS.items():
                    share, rate = measure(server, query, args.clients, args.window)
                    readings[kind].append((share, rate))
                    print(
                        f"round {round_ + 1} {kind:15} {share:.3f} core  {rate:5.1f} frames/s a client",
                        flush=True,
                    )
            problems = server.log_problems()
        finally:
            server.stop()
    alone = statistics.median(share for share, _ in readings["alone"])
    rows = []
    print(f"\n{'kind':15} {'server, core':>12} {'a client, ms/s':>15} {'frames/s':>9}")
    for kind, values in readings.items():
        share = statistics.median(s for s, _ in values)
        rate = statistics.median(r for _, r in values)
        per_client_ms = None if kind == "alone" else (share - alone) / args.clients * 1000
        shown = "" if per_client_ms is None else f"{per_client_ms:.1f}"
        print(f"{kind:15} {share:12.3f} {shown:>15} {rate:9.1f}")
        rows.append(
            {
                "kind": kind,
                "server_cpu_cores": round(share, 3),
                "per_client_ms_per_s": per_client_ms,
                "frames_per_client_s": round(rate, 1),
                "readings": values,
            }
        )
    save_results(
        "echo_cost", {"machine": machine, "args": vars(args), "rows": rows, "log_problems": problems}
    )


if __name__ == "__main__":
    main()
