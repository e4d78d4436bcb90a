"""Save → Run → first output line, as the page does it through the workspace API: a node file
saved with ``PUT /api/workspace/files/...``, run with ``POST /api/run``, its output read on
``WS /ws/launches/{id}/output`` until the node's first line, then stopped (``DELETE``) until the
socket's ``end``. Against a live server (``--launch rocket``, the graph on Zenoh) in a temporary
folder; prints p50/p95 of save, run, first line and the whole, and of stop → end."""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import tempfile
import time
from pathlib import Path

import httpx
from live_server import LiveServer
from machine import machine_info
from websockets.sync.client import connect

PACKAGE = "bench_pkg"
NODE = """import time

import rclpy
from rclpy.node import Node


def main():
    rclpy.init()
    node = Node('bench_node')
    node.get_logger().info('first line {n}')
    try:
        while True:
            time.sleep(0.1)
    except KeyboardInterrupt:
        pass
    finally:
        rclpy.try_shutdown()
"""
READ_S = 60.0


def percentiles(values: list[float]) -> dict[str, float]:
    ordered = sorted(values)
    return {
        "p50": round(statistics.median(ordered), 1),
        "p95": round(ordered[min(len(ordered) - 1, round(0.95 * (len(ordered) - 1)))], 1),
        "max": round(ordered[-1], 1),
    }


def one_try(server: LiveServer, http: httpx.Client, n: int) -> dict[str, float]:
    path = f"/api/workspace/files/src/{PACKAGE}/{PACKAGE}/bench_node.py"
    started = time.perf_counter()
    saved = http.put(path, json={"text": NODE.format(n=n)})
    saved.raise_for_status()
    after_save = time.perf_counter()
    ran = http.post("/api/run", json={"package": PACKAGE, "executable": "bench_node"})
    ran.raise_for_status()
    after_run = time.perf_counter()
    group = ran.json()["id"]
    with connect(f"{server.ws_url}/ws/launches/{group}/output", max_size=None) as ws:
        while True:
            frame = json.loads(ws.recv(timeout=READ_S))
            if frame["type"] == "line" and f"first line {n}" in frame["text"]:
                break
        first_line = time.perf_counter()
        http.delete(f"/api/launches/{group}").raise_for_status()
        while json.loads(ws.recv(timeout=READ_S))["type"] != "end":
            pass
        ended = time.perf_counter()
    return {
        "save_ms": (after_save - started) * 1000,
        "run_ms": (after_run - after_save) * 1000,
        "first_line_ms": (first_line - after_run) * 1000,
        "save_to_first_line_ms": (first_line - started) * 1000,
        "stop_to_end_ms": (ended - first_line) * 1000,
    }


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--tries", type=int, default=10)
    parser.add_argument("--json", type=Path, default=Path("bench/results/workspace_run.json"))
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        server = LiveServer(Path(folder), "rocket", "start_delay:=3600")
        try:
            with httpx.Client(base_url=server.url, timeout=60.0) as http:
                body = {"name": PACKAGE, "build_type": "ament_python", "node_name": "bench_node"}
                http.post("/api/workspace/packages", json=body).raise_for_status()
                tries = [one_try(server, http, n) for n in range(args.tries)]
        finally:
            server.stop()
    result = {
        "machine": machine_info(),
        "tries": args.tries,
        **{key: percentiles([t[key] for t in tries]) for key in tries[0]},
    }
    print(json.dumps(result, indent=2))
    args.json.parent.mkdir(parents=True, exist_ok=True)
    args.json.write_text(json.dumps(result, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
