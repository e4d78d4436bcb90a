"""Bench: a class told "run it now", measured from outside.

    .venv/bin/python bench/class_burst.py [--worlds 30] [--per-world 2] [--joined-timeout-s 300]

A class server (``--classroom --launch fly``, its Zenoh router on a free loopback port) with
``--worlds`` students joined, one world each. Then ``--worlds`` × ``--per-world`` ``ros2lab run``
of the handout's keyboard manager (examples/workspace, rocketship), each with its student's token
and a node name of its own, all started at once, as a class does. What is measured:

* the time from the first ``Popen`` until every node is in its own world's ``GET /api/nodes``
  (each world polled in turn, every 0.5 s);
* every world's dynamics timer rate over that time (``flightgoggles_uav_dynamics``' timer calls,
  read with the world's token before the starts and once all are joined): median and lowest;
* the class server's CPU (cores) over that time, the share of the machine's CPU time the
  hypervisor stole, and the load average;
* then, one second later, each node process's RSS (the ``runner`` children of the ``ros2lab run``
  processes): median, max and sum.

Every child is ended by its own id (Ctrl-C to each ``ros2lab run``, which passes it on). Prints
the machine (bench/machine.py) and one JSON object, also written to bench/results/class_burst.json.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

import httpx
from live_server import READER, LiveServer, end, rss_mib
from machine import machine_info, save_results

CODE = "BURST1"
DYNAMICS = "flightgoggles_uav_dynamics"
WORKSPACE = REPO / "examples" / "workspace"
ROS2LAB = str(Path(sys.executable).parent / "ros2lab")
POLL_S = 0.5


def cpu_jiffies() -> tuple[int, int]:
    """(steal, total) jiffies of every CPU so far (/proc/stat's first line)."""
    values = [int(v) for v in Path("/proc/stat").read_text().split("\n", 1)[0].split()[1:9]]
    return values[7], sum(values)


def process_cpu_s(pid: int) -> float:
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def get(server: LiveServer, token: str, path: str) -> Any:
    reply = READER.get(server.url + path, headers={"Authorization": f"Bearer {token}"})
    reply.raise_for_status()
    return reply.json()


def dynamics_calls(server: LiveServer, token: str) -> tuple[int, float]:
    timers = get(server, token, f"/api/nodes/{DYNAMICS}")["timers"]
    return int(timers[0]["calls"]), time.monotonic()


def children(pid: int) -> list[int]:
    try:
        return [int(p) for p in Path(f"/proc/{pid}/task/{pid}/children").read_text().split()]
    except FileNotFoundError:
        return []


def start(server: LiveServer, token: str, node: str, env: dict[str, str]) -> subprocess.Popen[bytes]:
    """``ros2lab run`` of the handout's keyboard manager as ``node``, in the world of ``token``."""
    argv = [
        ROS2LAB,
        "--url",
        server.url,
        "run",
        "--workspace",
        str(WORKSPACE),
        "rocketship",
        "keyboard_manager.py",
    ]
    return subprocess.Popen(
        [*argv, "--ros-args", "-r", f"__node:={node}"],
        env={**env, "ROS2LAB_TOKEN": token}, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
    )  # fmt: skip


def burst(server: LiveServer, tokens: dict[str, str], per_world: int, timeout_s: float) -> dict[str, Any]:
    wanted = {w: {f"/{w}_node{i}" for i in range(per_world)} for w in tokens}
    steal0, total0 = cpu_jiffies()
    cpu0 = process_cpu_s(server.proc.pid)
    before = {w: dynamics_calls(server, t) for w, t in tokens.items()}
    env = {k: v for k, v in os.environ.items() if k not in ("ROS_DOMAIN_ID", "ROS2LAB_WORKSPACE")}
    t0 = time.monotonic()
    runs = [
        start(server, tokens[w], name.lstrip("/"), env)
        for w, names in wanted.items()
        for name in sorted(names)
    ]
    try:
        pending = dict(wanted)
        joined_at: list[float] = []
        unanswered = 0
        while pending and time.monotonic() - t0 < timeout_s:
            for w in list(pending):
                try:
                    listed = {n["name"] for n in get(server, tokens[w], "/api/nodes")}
                except httpx.TimeoutException:  # a starved server: not yet, and counted
                    unanswered += 1
                    continue
                if pending[w] <= listed:
                    del pending[w]
                    joined_at.append(time.monotonic() - t0)
            time.sleep(POLL_S)
        all_joined_s = time.monotonic() - t0 if not pending else None
        after = {w: dynamics_calls(server, t) for w, t in tokens.items()}
        cpu1 = process_cpu_s(server.proc.pid)
        steal1, total1 = cpu_jiffies()
        window_s = max(t for _, t in after.values()) - min(t for _, t in before.values())
        time.sleep(1.0)
        node_rss = [rss_mib(c) for run in runs for c in children(run.pid)]
        exited = sum(1 for run in runs if run.poll() is not None)
    finally:
        for run in runs:
            end(run)
    rates = sorted((after[w][0] - before[w][0]) / (after[w][1] - before[w][1]) for w in tokens)
    return {
        "nodes": len(runs),
        "all_joined_s": round(all_joined_s, 1) if all_joined_s is not None else None,
        "not_joined_worlds": sorted(pending),
        "node_lists_unanswered_in_60_s": unanswered,
        "ros2lab_exited_early": exited,
        "worlds_joined_s": {"median": round(statistics.median(joined_at), 1)} if joined_at else None,
        "dynamics_hz": {"median": round(statistics.median(rates), 1), "lowest": round(rates[0], 1)},
        "server_cpu_cores": round((cpu1 - cpu0) / window_s, 2),
        "stolen": round((steal1 - steal0) / max(1, total1 - total0), 4),
        "load_average_after": list(os.getloadavg()),
        "node_rss_mib": {
            "median": round(statistics.median(node_rss), 1), "max": round(max(node_rss), 1),
            "sum": round(sum(node_rss), 1), "count": len(node_rss),
        } if node_rss else None,
    }  # fmt: skip


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--worlds", type=int, default=30)
    parser.add_argument("--per-world", type=int, default=2)
    parser.add_argument("--joined-timeout-s", type=float, default=300.0)
    args = parser.parse_args(argv)
    print(json.dumps(machine_info()), flush=True)
    root = Path(tempfile.mkdtemp(prefix="class_burst_"))
    server = LiveServer(root, "fly", "--classroom", "--class-code", CODE, "--max-worlds", str(args.worlds))
    try:
        tokens: dict[str, str] = {}
        for i in range(args.worlds):
            reply = httpx.post(
                f"{server.url}/api/classroom/join",
                json={"name": f"student{i:02d}", "code": CODE},
                timeout=180,
            )
            reply.raise_for_status()
            tokens[reply.json()["world"]] = reply.json()["token"]
        time.sleep(3.0)  # every world flying before the starts
        results = {"args": vars(args), **burst(server, tokens, args.per_world, args.joined_timeout_s)}
    finally:
        server.stop()
        shutil.rmtree(root, ignore_errors=True)
    print(json.dumps(results, indent=1))
    save_results("class_burst", results)
    return 0


if __name__ == "__main__":
    sys.exit(main())
