"""Bench: the client library in a node process, measured from outside.

    .venv/bin/python bench/node_client.py [--tries 5] [--rate 1000] [--duration-s 10] [--warmup-s 2]
                                          [--rounds 2] [--skip start|exchange]

One lab (``--launch rocket start_delay:=3600``, its Zenoh router on a free loopback port) serves
as the router for every process below; each process is a Zenoh peer connecting to it, listening
on 127.0.0.1 only, multicast scouting off; every child is ended by its own pid. What is measured:

* start → listed, and RSS: the handout's keyboard manager (examples/workspace, rocketship) run as
  the lab's launcher runs a node file, ``python -m node_runtime.process.runner FILE`` with the lab's
  ``ZENOH_CONFIG_OVERRIDE``: from just before ``Popen`` until ``/KeyboardManagerNode`` is in ``GET
  /api/nodes`` (polled every 20 ms); then, one second later, its VmRSS (/proc/PID/status); then
  Ctrl-C. Median and max over ``--tries``.
* 1 kHz between two node processes: a publisher node (``bench/zenoh_graph.py``'s: std_msgs/String
  of 49 CDR bytes carrying its send time, ``--warmup-s`` at 50 Hz, then ``--rate`` Hz for
  ``--duration-s``) and a subscriber node (this project's rclpy, its callback notes the arrival
  time); latency = arrival − send time (CLOCK_REALTIME, one machine) of each measured message:
  p50, p99, max, and how many arrived. Against two bare ``eclipse-zenoh`` peer processes doing the
  same (same payload bytes, same rate, same router, a plain put and a plain subscriber). The two
  pairs alternate ``--rounds`` times in one run.

Prints the machine (bench/machine.py) and one JSON object, also written to
bench/results/node_client.json.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import select
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))  # run as a script from anywhere: the app's packages live at the root

import httpx
from live_server import LiveServer, end, rss_mib
from machine import machine_info, save_results
from zenoh_graph import (
    BARE_KEY,
    TOPIC,
    child_env,
    parse_text,
    read_json_line,
    summarize,
    zenoh_config,
)

KEYBOARD_MANAGER = REPO / "examples" / "workspace" / "src" / "rocketship" / "src" / "keyboard_manager.py"
NODE_NAME = "/KeyboardManagerNode"
LISTED_TIMEOUT_S = 30.0
SETTLE_S = 1.0
CHILD_GRACE_S = 60.0


# -- the children (``--role``) -----------------------------------------------------------------
def _serve_until_stop(got: list[tuple[int, bytes]], max_s: float) -> None:
    """Say ``ready``, wait for ``stop`` on stdin, then print the summary of what ``got`` holds."""
    print(json.dumps({"event": "ready"}), flush=True)
    deadline = time.monotonic() + max_s
    while time.monotonic() < deadline:
        ready, _, _ = select.select([sys.stdin], [], [], 0.5)
        if ready and sys.stdin.readline().strip() in ("stop", ""):
            break
    rows = []
    for recv_ns, payload in list(got):
        phase, seq, sent_ns = parse_text(payload.decode())
        if phase == "m":
            rows.append((seq, sent_ns, recv_ns))
    print(json.dumps({"event": "summary", **summarize(rows)}), flush=True)


def role_rclpy_sub(args: argparse.Namespace) -> int:
    import threading

    import rclpy
    from rclpy.executors import ExternalShutdownException
    from rclpy.node import Node
    from std_msgs.msg import String

    got: list[tuple[int, bytes]] = []
    rclpy.init(args=["bench_sub"])
    node = Node("bench_sub")
    node.create_subscription(String, TOPIC, lambda msg: got.append((time.time_ns(), msg.data.encode())), 1000)

    def spin() -> None:
        with contextlib.suppress(ExternalShutdownException):  # the shutdown below ends it
            rclpy.spin(node)

    spinner = threading.Thread(target=spin, daemon=True)
    spinner.start()
    _serve_until_stop(got, args.max_s)
    rclpy.shutdown()
    return 0


def role_bare_sub(args: argparse.Namespace) -> int:
    import zenoh

    got: list[tuple[int, bytes]] = []

    def on_sample(sample: zenoh.Sample) -> None:
        got.append((time.time_ns(), sample.payload.to_bytes()[8:-1]))  # the String's characters

    session = zenoh.open(zenoh_config("peer", ["tcp/127.0.0.1:0"], [args.connect]))
    try:
        sub = session.declare_subscriber(BARE_KEY, on_sample)
        _serve_until_stop(got, args.max_s)
        sub.undeclare()
    finally:
        session.close()
    return 0


# -- the parent --------------------------------------------------------------------------------
def start_to_listed(server: LiveServer, tries: int) -> dict[str, Any]:
    env = child_env(f"tcp/127.0.0.1:{server.zenoh_port}")
    listed_s: list[float] = []
    rss: list[float] = []
    for _ in range(tries):
        t0 = time.monotonic()
        proc = subprocess.Popen(
            [sys.executable, "-m", "node_runtime.process.runner", str(KEYBOARD_MANAGER)],
            cwd=REPO,
            env=env,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        try:
            while not any(n["name"] == NODE_NAME for n in _nodes(server)):
                if time.monotonic() - t0 > LISTED_TIMEOUT_S or proc.poll() is not None:
                    raise RuntimeError(f"{NODE_NAME} never listed (exit code {proc.poll()})")
                time.sleep(0.02)
            listed_s.append(time.monotonic() - t0)
            time.sleep(SETTLE_S)
            rss.append(rss_mib(proc.pid))
        finally:
            end(proc)
        while any(n["name"] == NODE_NAME for n in _nodes(server)):  # gone before the next try
            time.sleep(0.05)
    return {
        "tries": tries,
        "start_to_listed_s": {
            "median": round(statistics.median(listed_s), 3),
            "max": round(max(listed_s), 3),
        },
        "rss_mib": {"median": round(statistics.median(rss), 1), "max": round(max(rss), 1)},
    }


def _nodes(server: LiveServer) -> list[dict[str, Any]]:
    return list(httpx.get(server.url + "/api/nodes", timeout=10.0).json())


def exchange(kind: str, router: str, args: argparse.Namespace) -> dict[str, Any]:
    """One publisher and one subscriber process of ``kind`` (``rclpy`` or ``bare``)."""
    common = ["--connect", router, "--max-s", str(args.warmup_s + args.duration_s + CHILD_GRACE_S)]
    env = child_env(router)
    sub = subprocess.Popen(
        [sys.executable, __file__, "--role", f"{kind}-sub", *common],
        cwd=REPO,
        env=env,
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        text=True,
    )
    pub: subprocess.Popen[str] | None = None
    try:
        read_json_line(sub, CHILD_GRACE_S)  # ready
        pub = subprocess.Popen(
            [
                sys.executable,
                str(REPO / "bench" / "zenoh_graph.py"),
                "--role",
                f"{kind}-pub",
                *common[:2],
                "--rate",
                str(args.rate),
                "--duration",
                str(args.duration_s),
                "--warmup",
                str(args.warmup_s),
            ],
            cwd=REPO,
            env=env,
            stdout=subprocess.PIPE,
            text=True,
        )
        sent = read_json_line(pub, args.warmup_s + args.duration_s + CHILD_GRACE_S)
        time.sleep(0.5)  # the last samples in flight
        assert sub.stdin is not None
        sub.stdin.write("stop\n")
        sub.stdin.flush()
        summary = read_json_line(sub, CHILD_GRACE_S)
        return {"sent": sent["sent"], **{k: v for k, v in summary.items() if k != "event"}}
    finally:
        for proc in (pub, sub):
            if proc is not None:
                end(proc)
                for stream in (proc.stdin, proc.stdout):
                    if stream is not None:
                        stream.close()


def parse_args(argv: list[str] | None = None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--tries", type=int, default=5)
    parser.add_argument("--rate", type=float, default=1000.0)
    parser.add_argument("--duration-s", type=float, default=10.0)
    parser.add_argument("--warmup-s", type=float, default=2.0)
    parser.add_argument("--rounds", type=int, default=2)
    parser.add_argument("--skip", choices=["start", "exchange"], action="append", default=[])
    parser.add_argument("--role", choices=["rclpy-sub", "bare-sub"], help=argparse.SUPPRESS)
    parser.add_argument("--connect", help=argparse.SUPPRESS)
    parser.add_argument("--max-s", type=float, default=120.0, help=argparse.SUPPRESS)
    return parser.parse_args(argv)


def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)
    if args.role == "rclpy-sub":
        return role_rclpy_sub(args)
    if args.role == "bare-sub":
        return role_bare_sub(args)
    print(json.dumps(machine_info()), flush=True)
    root = Path(tempfile.mkdtemp(prefix="node_client_"))
    server = LiveServer(root, "rocket", "start_delay:=3600", "--no-foxglove")
    results: dict[str, Any] = {
        "args": {k: v for k, v in vars(args).items() if k not in ("role", "connect", "max_s")}
    }
    try:
        if "start" not in args.skip:
            results["keyboard_manager"] = start_to_listed(server, args.tries)
            print(json.dumps(results["keyboard_manager"]), flush=True)
        if "exchange" not in args.skip:
            router = f"tcp/127.0.0.1:{server.zenoh_port}"
            rounds: dict[str, list[dict[str, Any]]] = {"rclpy": [], "bare": []}
            for _ in range(args.rounds):
                for kind in ("rclpy", "bare"):
                    rounds[kind].append(exchange(kind, router, args))
                    print(json.dumps({kind: rounds[kind][-1]}), flush=True)
            results["exchange"] = rounds
    finally:
        server.stop()
        shutil.rmtree(root, ignore_errors=True)
    print(json.dumps(results, indent=1))
    save_results("node_client", results)
    return 0


if __name__ == "__main__":
    sys.exit(main())
