"""Bench: what an idle student node costs the machine, from outside its process.

    .venv/bin/python bench/node_idle.py [--nodes 3] [--window-s 20] [--rounds 3]

A lab (``--launch fly``, its Zenoh router on a free loopback port) and ``--nodes`` ``ros2lab run``
of the handout's keyboard manager (examples/workspace, rocketship), each with a node name of its
own: a node that handles keys on a 10 Hz timer and publishes ``/abort_takeoff`` on each tick, and
otherwise waits, as the 60 nodes of a class of 30 do once they run. Once every node is in the
lab's ``GET /api/nodes``, ``--rounds`` windows of ``--window-s`` seconds each read every node
process's threads from ``/proc/PID/task/TID/schedstat`` (time on a CPU, in nanoseconds) and
``status`` (voluntary context switches, the times a thread went to sleep): per node, the share of
one core its Python threads took (the interpreter's, where the timer's callback and the executor
run) and its Zenoh runtime's threads, and the Python threads' sleeps a second (a blocking wait
each). Reported: the median over nodes and rounds of each.

Every child is ended by its own id (Ctrl-C to each ``ros2lab run``, which passes it on). Prints
the machine (bench/machine.py) and one JSON object, also written to bench/results/node_idle.json.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from class_burst import ROS2LAB, WORKSPACE, descendants, is_runner
from live_server import READER, LiveServer, end
from machine import machine_info, save_results

JOIN_TIMEOUT_S = 60.0
PYTHON_THREAD = "python"  # the interpreter's threads keep the program's name; Zenoh names its own


def thread_times(pid: int) -> dict[str, tuple[int, int]]:
    """Per kind of thread (``python`` or Zenoh's runtime): (ns on a CPU, voluntary switches)."""
    out: dict[str, tuple[int, int]] = {}
    for task in Path(f"/proc/{pid}/task").iterdir():
        try:
            ns = int((task / "schedstat").read_text().split()[0])
            status = (task / "status").read_text()
        except FileNotFoundError:
            continue  # a thread that ended meanwhile
        switches = int(status.split("voluntary_ctxt_switches:")[1].split()[0])
        kind = PYTHON_THREAD if (task / "comm").read_text().strip() == PYTHON_THREAD else "zenoh"
        ns0, sw0 = out.get(kind, (0, 0))
        out[kind] = (ns0 + ns, sw0 + switches)
    return out


def window(pids: list[int], seconds: float) -> list[dict[str, float]]:
    before = {pid: thread_times(pid) for pid in pids}
    start = time.monotonic()
    time.sleep(seconds)
    after = {pid: thread_times(pid) for pid in pids}
    wall = time.monotonic() - start
    rows = []
    for pid in pids:
        row: dict[str, float] = {}
        for kind in (PYTHON_THREAD, "zenoh"):
            ns0, sw0 = before[pid].get(kind, (0, 0))
            ns1, sw1 = after[pid].get(kind, (0, 0))
            row[f"{kind}_pct"] = 100.0 * (ns1 - ns0) / 1e9 / wall
            if kind == PYTHON_THREAD:
                row["python_sleeps_per_s"] = (sw1 - sw0) / wall
        rows.append(row)
    return rows


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--nodes", type=int, default=3)
    parser.add_argument("--window-s", type=float, default=20.0)
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args(argv)
    print(json.dumps(machine_info()))
    with tempfile.TemporaryDirectory() as work:
        server = LiveServer(Path(work), "fly")
        procs: list[subprocess.Popen[bytes]] = []
        try:
            names = [f"idle{i}" for i in range(args.nodes)]
            run = [ROS2LAB, "--url", server.url, "run", "--workspace", str(WORKSPACE), "rocketship"]
            for name in names:
                argv = [*run, "keyboard_manager.py", "--ros-args", "-r", f"__node:={name}"]
                procs.append(subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
            deadline = time.monotonic() + JOIN_TIMEOUT_S
            while True:
                listed = {n["name"] for n in READER.get(f"{server.url}/api/nodes").json()}
                if all(f"/{name}" in listed for name in names):
                    break
                if time.monotonic() > deadline:
                    raise RuntimeError(f"not every node joined in {JOIN_TIMEOUT_S} s: {sorted(listed)}")
                time.sleep(0.2)
            time.sleep(2.0)  # past the join's own traffic
            pids = [pid for proc in procs for pid in descendants(proc.pid) if is_runner(pid)]
            rows = [row for _ in range(args.rounds) for row in window(pids, args.window_s)]
        finally:
            for proc in procs:
                end(proc)
            server.stop()
    result: dict[str, Any] = {"args": vars(args), "node_processes": len(pids)}
    for key in ("python_pct", "zenoh_pct", "python_sleeps_per_s"):
        result[key] = {"median": round(statistics.median(r[key] for r in rows), 3)}
        result[key]["max"] = round(max(r[key] for r in rows), 3)
    print(json.dumps(result, indent=1))
    save_results("node_idle", result)
    return 0


if __name__ == "__main__":
    sys.exit(main())
