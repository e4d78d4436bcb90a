"""Bench: what the class's own graph costs (node_runtime/transport/domain_bridge.py): every world's GPS
watched under its name in the class domain, against the same GPS watched in each world's own domain.

    .venv/bin/python bench/class_graph.py [--worlds 10] [--window 20] [--rounds 3]

``python -m server --classroom --launch fly`` in a child process, ``--worlds`` students joined
through the REST API. A watcher in this process (a Zenoh client logged in as the class, as the
instructor's ROS 2 tools would be with ``ros2lab env``) takes, in turn for ``--window`` seconds:

- ``idle``: watches nothing;
- ``direct``: every world's ``/uav/sensors/gps`` in its own domain (``<d>/uav/sensors/gps/...``);
- ``bridged``: every world's ``/<world>/uav/sensors/gps`` in the class domain, through the bridge.

For each: the server's CPU (share of one core, from /proc), the worlds' dynamics tick lateness
(p99 of each world's 100 Hz timer over the window, median over worlds), the samples a second the watcher got,
and their latency (arrival against the attachment's source timestamp, which the bridge keeps; one
clock, one machine). Phases alternate over ``--rounds``; medians are reported, with the bridged
phase's extra CPU over idle against the direct one's. The child is ended by its own pid.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import threading
import time
from pathlib import Path
from typing import Any

import httpx
import zenoh

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
sys.path.insert(0, str(Path(__file__).resolve().parent))
from classroom_worlds import cpu_s
from live_server import LiveServer
from machine import machine_info, save_results

from node_runtime.msgs.wire import dds_type_name, type_hash
from node_runtime.transport.acl import Credentials
from node_runtime.transport.attachment import Attachment
from node_runtime.transport.config import ZenohSettings
from node_runtime.transport.keys import data_key
from node_runtime.transport.session import build_config

CODE = "GRAPH1"
DYNAMICS = "flightgoggles_uav_dynamics"
POSE = "geometry_msgs/msg/PoseStamped"
SETTLE_S = 3.0  # after a phase's subscriptions, before its window: the routes settle
MAX_LATENCIES = 200_000


class Watcher:
    """Counts samples and their latency from every subscription it holds; thread-safe."""

    def __init__(self, session: Any) -> None:
        self.session = session
        self.subs: list[Any] = []
        self.lock = threading.Lock()
        self.count = 0
        self.latencies_ms: list[float] = []

    def _on(self, sample: zenoh.Sample) -> None:
        now = time.time_ns()
        raw = sample.attachment
        attachment = Attachment.unpack(raw.to_bytes() if raw is not None else None)
        with self.lock:
            self.count += 1
            if attachment is not None and len(self.latencies_ms) < MAX_LATENCIES:
                self.latencies_ms.append((now - attachment.source_timestamp_ns) / 1e6)

    def watch(self, keys: list[str]) -> None:
        self.subs = [self.session.declare_subscriber(key, self._on) for key in keys]

    def stop(self) -> None:
        for sub in self.subs:
            sub.undeclare()
        self.subs = []

    def take(self) -> tuple[int, list[float]]:
        with self.lock:
            out = self.count, self.latencies_ms
            self.count, self.latencies_ms = 0, []
        return out


def tick_lateness_p99_ms(server: LiveServer, instructor: dict[str, str], worlds: list[str]) -> float:
    """The median over worlds of their dynamics timer's lateness p99 (its last 2000 ticks: 20 s)."""
    p99s = []
    for world in worlds:
        info = httpx.get(
            f"{server.url}/api/nodes/{DYNAMICS}", headers={**instructor, "X-Lab-World": world}, timeout=10
        ).json()
        p99s.append(info["timers"][0]["lateness_p99_ms"])
    return float(statistics.median(p99s))


def phase(
    server: LiveServer,
    watcher: Watcher,
    keys: list[str],
    window_s: float,
    instructor: dict[str, str],
    worlds: list[str],
) -> dict[str, Any]:
    watcher.watch(keys)
    time.sleep(SETTLE_S if keys else 0.5)
    watcher.take()
    cpu0, t0 = cpu_s(server.proc.pid), time.monotonic()
    time.sleep(window_s)
    cpu1, t1 = cpu_s(server.proc.pid), time.monotonic()
    count, latencies = watcher.take()
    lateness = tick_lateness_p99_ms(server, instructor, worlds)
    watcher.stop()
    latencies.sort()
    return {
        "cpu_core_share": (cpu1 - cpu0) / (t1 - t0),
        "tick_lateness_p99_ms": lateness,
        "samples_per_s": count / (t1 - t0),
        "latency_p50_ms": latencies[len(latencies) // 2] if latencies else None,
        "latency_p99_ms": latencies[int(len(latencies) * 0.99)] if latencies else None,
    }


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--worlds", type=int, default=10)
    parser.add_argument(
        "--window",
        type=float,
        default=20.0,
        help="seconds measured per phase (20: the ticks' lateness is over the last 20 s)",
    )
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    info = machine_info()
    print(f"machine: {info['cpu_model']}, {info['nproc']} CPUs, Python {info['python']}", flush=True)
    rows: dict[str, list[dict[str, Any]]] = {"idle": [], "direct": [], "bridged": []}
    with tempfile.TemporaryDirectory() as tmp:
        server = LiveServer(
            Path(tmp),
            "fly",
            "--classroom",
            "--class-code",
            CODE,
            "--max-worlds",
            str(args.worlds),
            "--no-foxglove",
            "--workers",
            "0",  # every world on the class server's own graph
        )
        try:
            instructor = {"Authorization": f"Bearer {server.instructor_token()}"}
            for i in range(args.worlds):
                reply = httpx.post(
                    f"{server.url}/api/classroom/join",
                    json={"name": f"student {i}", "code": CODE},
                    timeout=30,
                )
                reply.raise_for_status()
            worlds = httpx.get(f"{server.url}/api/classroom/worlds", headers=instructor, timeout=30).json()[
                "worlds"
            ]
            names = [w["world"] for w in worlds]
            join = httpx.get(f"{server.url}/api/zenoh/join", headers=instructor, timeout=30).json()
            dds, digest = dds_type_name(POSE), type_hash(POSE)
            keys = {
                "idle": [],
                "direct": [data_key(w["domain_id"], "/uav/sensors/gps", dds, digest) for w in worlds],
                "bridged": [
                    data_key(join["domain_id"], f"/{w['world']}/uav/sensors/gps", dds, digest) for w in worlds
                ],
            }
            settings = ZenohSettings(
                mode="client",
                listen=(),
                connect=(join["router"],),
                login=Credentials(join["user"], join["password"]),
            )
            with zenoh.open(build_config(settings)) as session:
                watcher = Watcher(session)
                time.sleep(SETTLE_S)
                for r in range(args.rounds):
                    for name in ("idle", "direct", "bridged"):
                        row = phase(server, watcher, keys[name], args.window, instructor, names)
                        rows[name].append(row)
                        print(
                            f"round {r + 1} {name:>8}: {row['cpu_core_share']:.3f} core, tick p99 "
                            f"{row['tick_lateness_p99_ms']:.1f} ms, "
                            f"{row['samples_per_s']:.0f} samples/s, latency p50/p99 "
                            f"{row['latency_p50_ms']} / {row['latency_p99_ms']} ms",
                            flush=True,
                        )
            problems = server.log_problems()
        finally:
            server.stop()

    def med(name: str, field: str) -> float | None:
        values = [r[field] for r in rows[name] if r[field] is not None]
        return round(statistics.median(values), 3) if values else None

    summary = {name: {f: med(name, f) for f in rows[name][0]} for name in rows}
    idle = summary["idle"]["cpu_core_share"] or 0.0
    extra = {
        name: round((summary[name]["cpu_core_share"] or 0.0) - idle, 3) for name in ("direct", "bridged")
    }
    print(f"\n{args.worlds} fly worlds, medians over {args.rounds} rounds of {args.window:g} s:")
    print(
        f"{'watching':>9} {'CPU (core)':>10} {'tick p99 ms':>11} {'samples/s':>10} {'p50 ms':>8} {'p99 ms':>8}"
    )
    for name, row in summary.items():
        print(
            f"{name:>9} {row['cpu_core_share']:>10.3f} {row['tick_lateness_p99_ms']:>11.2f} {row['samples_per_s']:>10.0f} "
            f"{row['latency_p50_ms'] or 0:>8.2f} {row['latency_p99_ms'] or 0:>8.2f}"
        )
    if extra["direct"] > 0:
        print(
            f"server CPU for watching, bridged over direct: {extra['bridged'] / extra['direct']:.2f}x "
            f"(+{extra['bridged']:.3f} against +{extra['direct']:.3f} core)"
        )
    if problems:
        print("server log problems:", *problems[:5], sep="\n  ")
    save_results(
        "class_graph",
        {
            "machine": info,
            "worlds": args.worlds,
            "window_s": args.window,
            "rounds": rows,
            "summary": summary,
            "extra_cpu_over_idle": extra,
            "log_problems": problems[:5],
        },
    )


if __name__ == "__main__":
    main()
