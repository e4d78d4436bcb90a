"""Bench: the rosbridge endpoint with real roslibpy clients, and a client that stalls.

    .venv/bin/python bench/rosbridge_bench.py [--one-s 60] [--many 20] [--many-s 30] [--stall-s 300]

The server is ``python -m server --launch fly --no-foxglove --no-zenoh`` on a free loopback port:
the drone's dynamics publish /uav/sensors/gps (PoseStamped, header stamped with the bus's wall
clock) at 100 Hz.

* one client: roslibpy (Twisted) subscribed to /uav/sensors/gps for ``--one-s``: delivered rate,
  and latency from the message's header stamp to the callback (same machine, same clock), p50/p99.
* many clients: ``--many`` roslibpy clients subscribed to the same topic for ``--many-s``: the
  server's CPU (utime+stime from /proc over wall time, % of one core) and each client's rate.
* stalled client: a WebSocket handshake and subscriptions to every sensor topic written by hand
  on a socket that is then never read, for ``--stall-s``: the server's RSS growth, and the
  dynamics node's timer lateness (p99 over its last 2000 ticks, read every 10 s from the API),
  beside the same p99 read after 20 s with no client at all.
"""

from __future__ import annotations

import argparse
import json
import socket
import statistics
import subprocess
import sys
import threading
import time
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import httpx

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from live_server import end
from machine import machine_info
from startup_idle_keys import cpu_seconds, free_port, rss_mb

RESULTS = REPO / "bench" / "results"
TOPIC = "/uav/sensors/gps"
BASELINE_S = 20.0
STALL_TOPICS = ("/uav/sensors/gps", "/uav/sensors/velocity", "/uav/sensors/attitude", "/tf", "/rosout")


class Server:
    def __init__(self, workdir: Path) -> None:
        self.port = free_port()
        self.url = f"http://127.0.0.1:{self.port}"
        self.proc = subprocess.Popen(
            [
                sys.executable,
                "-m",
                "server",
                "--launch",
                "fly",
                "--port",
                str(self.port),
                "--no-foxglove",
                "--no-zenoh",
                "--log-level",
                "warning",
                "--bag-dir",
                str(workdir / "bags"),
            ],
            cwd=REPO,
        )
        deadline = time.monotonic() + 60
        while True:
            try:
                if httpx.get(f"{self.url}/api/health", timeout=1).status_code == 200:
                    break
            except httpx.HTTPError:
                pass
            if time.monotonic() > deadline or self.proc.poll() is not None:
                raise RuntimeError("the server did not start")
            time.sleep(0.1)
        time.sleep(3.0)  # take-off transient over

    def stop(self) -> None:
        end(self.proc, 15.0)


def subscribe_clients(url: str, n: int) -> tuple[list[Any], list[list[float]]]:
    import roslibpy

    clients, latencies = [], []
    for _ in range(n):
        ros = roslibpy.Ros(host=url)
        ros.run(timeout=30)
        lat: list[float] = []

        def on_msg(m: dict[str, Any], lat: list[float] = lat) -> None:
            stamp = m["header"]["stamp"]
            lat.append((time.time() - (stamp["sec"] + stamp["nanosec"] / 1e9)) * 1000)

        roslibpy.Topic(ros, TOPIC, "geometry_msgs/msg/PoseStamped").subscribe(on_msg)
        clients.append(ros)
        latencies.append(lat)
    return clients, latencies


def bench_clients(server: Server, n: int, duration_s: float) -> dict[str, Any]:
    clients, latencies = subscribe_clients(f"ws://127.0.0.1:{server.port}/rosbridge", n)
    time.sleep(2.0)
    for lat in latencies:
        lat.clear()
    cpu0, t0 = cpu_seconds(server.proc.pid), time.monotonic()
    time.sleep(duration_s)
    cpu1, t1 = cpu_seconds(server.proc.pid), time.monotonic()
    counts = [len(lat) for lat in latencies]
    every = sorted(x for lat in latencies for x in list(lat))
    for ros in clients:
        ros.close()
    return {
        "clients": n,
        "duration_s": duration_s,
        "rate_per_client_min": min(counts) / (t1 - t0),
        "rate_per_client_median": statistics.median(counts) / (t1 - t0),
        "latency_p50_ms": statistics.median(every) if every else None,
        "latency_p99_ms": every[int(0.99 * (len(every) - 1))] if every else None,
        "server_cpu_pct": 100 * (cpu1 - cpu0) / (t1 - t0),
    }


def lateness_p99_ms(server: Server) -> float | None:
    info = httpx.get(f"{server.url}/api/nodes/flightgoggles_uav_dynamics", timeout=5).json()
    return max((t["lateness_p99_ms"] or 0.0) for t in info["timers"])


def bench_stall(server: Server, duration_s: float) -> dict[str, Any]:
    time.sleep(BASELINE_S)  # no client: the ticks' own lateness on this machine, for comparison
    baseline = lateness_p99_ms(server)
    sock = socket.create_connection(("127.0.0.1", server.port))
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
    sock.sendall(
        b"GET /rosbridge HTTP/1.1\r\nHost: 127.0.0.1\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
        b"Sec-WebSocket-Version: 13\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n\r\n"
    )
    for topic in STALL_TOPICS:
        payload = json.dumps({"op": "subscribe", "topic": topic, "queue_length": 1000}).encode()
        sock.sendall(bytes([0x81, 0x80 | 126]) + len(payload).to_bytes(2, "big") + b"\0\0\0\0" + payload)
    rss0 = rss_mb(server.proc.pid)
    samples = []
    end = time.monotonic() + duration_s
    while time.monotonic() < end:
        time.sleep(10.0)
        samples.append({"rss_mb": rss_mb(server.proc.pid), "tick_lateness_p99_ms": lateness_p99_ms(server)})
    sock.close()
    return {
        "duration_s": duration_s,
        "tick_lateness_p99_ms_no_client": baseline,
        "rss_start_mb": rss0,
        "rss_end_mb": samples[-1]["rss_mb"],
        "rss_growth_mb": samples[-1]["rss_mb"] - rss0,
        "rss_max_mb": max(s["rss_mb"] for s in samples),
        "tick_lateness_p99_ms_max": max(s["tick_lateness_p99_ms"] or 0.0 for s in samples),
        "samples": samples,
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--one-s", type=float, default=60.0)
    parser.add_argument("--many", type=int, default=20)
    parser.add_argument("--many-s", type=float, default=30.0)
    parser.add_argument("--stall-s", type=float, default=300.0)
    args = parser.parse_args()
    RESULTS.mkdir(parents=True, exist_ok=True)
    results: dict[str, Any] = {"machine": machine_info(), "when": datetime.now(UTC).isoformat()}
    threading.excepthook = lambda a: None  # roslibpy's reactor thread at exit
    server = Server(RESULTS)
    try:
        results["one_client"] = bench_clients(server, 1, args.one_s)
        print("one client", results["one_client"], flush=True)
        results["many_clients"] = bench_clients(server, args.many, args.many_s)
        print("many clients", results["many_clients"], flush=True)
        results["stalled_client"] = bench_stall(server, args.stall_s)
        print("stalled", {k: v for k, v in results["stalled_client"].items() if k != "samples"}, flush=True)
    finally:
        server.stop()
    out = RESULTS / f"rosbridge_{datetime.now(UTC).strftime('%Y%m%dT%H%M%S')}.json"
    out.write_text(json.dumps(results, indent=2))
    print(f"written to {out.relative_to(REPO)}")


if __name__ == "__main__":
    main()
