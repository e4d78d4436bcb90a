"""Bench: a student's ordinary calls, answered by a world on the class server and by one on a world
worker (passed on by the class server).

    .venv/bin/python bench/proxied_calls.py [--worlds 30] [--calls 200]

A class server (``--classroom --launch fly --workers auto``) with ``--worlds`` students joined
(the class spreads to a world worker on its machine from the tenth), the handout's keyboard
manager saved in each student's workspace. Then, for one student whose world the class server
runs and one whose world runs on the worker, each of a page's ordinary calls (``GET
/api/nodes``, ``/api/topics``, ``/api/workspace/files``, the keyboard manager's file, and
``/api/health``) ``--calls`` times one after the other over one kept-alive connection, as a page
makes them: the median and p99 time to the whole answer, and what each call cost the class
server's loop thread (where its own worlds tick): its CPU over the calls (``/proc``'s schedstat),
less what it takes in as long with no call (measured just before), per call. Prints the machine
and one JSON object, also written to bench/results/proxied_calls.json.
"""

from __future__ import annotations

import argparse
import json
import shutil
import statistics
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path
from typing import Any

import httpx
from class_burst import CODE, MANAGER, join_class, places, save_manager
from live_server import LiveServer
from machine import machine_info, save_results

PATHS = (
    "/api/nodes",
    "/api/topics",
    "/api/workspace/files",
    f"/api/workspace/files/{MANAGER}",
    "/api/health",
)
WARM_CALLS = 20
SETTLE_S = 5.0  # every world flying, the worker's hello answered


def loop_cpu_s(pid: int) -> float:
    """Seconds the main thread of ``pid`` (a server's loop) has run so far."""
    return int(Path(f"/proc/{pid}/task/{pid}/schedstat").read_text().split()[0]) / 1e9


def timed_calls(client: httpx.Client, url: str, token: str, calls: int, pid: int) -> dict[str, float]:
    """``calls`` GETs of ``url`` with ``token``, one after the other: time to the whole answer, and
    the loop CPU of server ``pid`` each took beyond its worlds' own (read over as long just before)."""
    headers = {"Authorization": f"Bearer {token}"}
    for _ in range(WARM_CALLS):
        client.get(url, headers=headers).raise_for_status()
    took: list[float] = []
    start, cpu0 = time.perf_counter(), loop_cpu_s(pid)
    for _ in range(calls):
        before = time.perf_counter()
        client.get(url, headers=headers).raise_for_status()
        took.append(time.perf_counter() - before)
    window_s, cpu_s = time.perf_counter() - start, loop_cpu_s(pid) - cpu0
    quiet0 = loop_cpu_s(pid)
    time.sleep(window_s)
    quiet_s = loop_cpu_s(pid) - quiet0
    took.sort()
    return {
        "median_ms": round(1000 * statistics.median(took), 2),
        "p99_ms": round(1000 * took[int(0.99 * (len(took) - 1))], 2),
        "loop_cpu_ms_per_call": round(1000 * (cpu_s - quiet_s) / calls, 3),
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--worlds", type=int, default=30)
    parser.add_argument("--calls", type=int, default=200)
    args = parser.parse_args(argv)
    print(json.dumps(machine_info()), flush=True)
    root = Path(tempfile.mkdtemp(prefix="proxied_calls_"))
    server = LiveServer(root, "fly", "--classroom", "--class-code", CODE, "--max-worlds", str(args.worlds))
    try:
        tokens, _ = join_class(server, args.worlds)
        for token in tokens.values():
            save_manager(server, token)
        time.sleep(SETTLE_S)
        where = places(server)
        student = {}
        for world, place in where.items():
            student.setdefault("server" if place == "server" else "worker", world)
        if set(student) != {"server", "worker"}:
            raise RuntimeError(f"the class did not spread over a worker: {where}")
        results: dict[str, Any] = {"args": vars(args), "worlds_by_place": dict(Counter(where.values()))}
        with httpx.Client(timeout=30.0) as client:
            for place, world in student.items():
                results[f"world_on_{place}"] = {
                    path: timed_calls(client, server.url + path, tokens[world], args.calls, server.proc.pid)
                    for path in PATHS
                }
    finally:
        server.stop()
        shutil.rmtree(root, ignore_errors=True)
    print(json.dumps(results, indent=1))
    save_results("proxied_calls", results)
    return 0


if __name__ == "__main__":
    sys.exit(main())
