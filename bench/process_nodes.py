"""Bench: student nodes as processes of their own, measured from outside the app.

    .venv/bin/python bench/process_nodes.py [--run-tries 5] [--abort-samples 30] [--cpu-window-s 20]
                                            [--publishers 5] [--publish-hz 20]
                                            [--reflex-samples 200]

Every app and Zenoh session binds 127.0.0.1 on a free port (multicast scouting off: the app's
router is configured so, and node processes are peers that connect to it); every child process
is ended by its own pid. The workspace is a temporary copy of examples/workspace (the handout's
files) plus one package of this bench's own, ``benchpub``. What is measured:

* ``ros2lab run``: from just before ``Popen`` of ``python -m server --url URL run rocketship
  keyboard_manager.py`` (run in the folder holding ./workspace, as a student runs it) until
  ``/KeyboardManagerNode`` is in the app's ``GET /api/nodes`` (polled every 20 ms); median and
  max over ``--run-tries``. Then Ctrl-C (SIGINT to the command's pid, which passes it on) and
  the time until the node leaves the list. The app: ``--launch rocket start_delay:=3600`` with
  the workspace (so its keyboard manager, ``/KeyboardManager``, is the student's file as a
  process too).
* keydown -> abort round trip: the key "a" sent on the page's key channel (``/ws/keys``: a keydown
  frame, then a keyup) until the echo WebSocket on ``/abort_takeoff`` (``/ws/topics/abort_takeoff``)
  brings a frame with ``data: true``; both sockets are read here, on one monotonic clock. The
  abort latches, so before each sample ``POST /api/rocket/reset`` restarts the rocket's nodes (the
  keyboard manager's process too), and the sample waits for a fresh manager: a ``false`` frame
  after the reset, then ``--settle-s`` with no ``true`` frame (the old process gone, the new one's
  /keydown route in place). Also reported: ``app_callback`` (the echo frame's ``received``, read in
  the app's subscription callback on its SystemClock, minus the send instant on CLOCK_REALTIME),
  and ``reset_to_fresh`` (how long the reset takes to give a publishing manager). Two apps run
  side by side and their samples alternate: the student's keyboard manager as a process (the
  app above), and the lab's own one in the app's process (``--workspace`` a missing folder). The
  manager handles keys on a 10 Hz timer, as the handout's does: up to 100 ms of every sample is
  that timer's wait, alike in both.
* ``/keydown`` → a process node's callback → its answer back in the app (the transport's round
  trip, with no timer in it): ``benchpub``'s ``reflex.py``, started by ``POST /api/run``, publishes
  on ``/bench_reflex`` in its ``/keydown`` callback. The key "x" (no rocket node acts on it) is
  sent on ``/ws/keys`` ``--reflex-samples`` times, 50 ms apart; two echo WebSockets give, on the
  app's clock inside its subscription callbacks, when ``/keydown`` was published in the app and
  when the answer arrived: ``keydown_to_answer_in_app`` is their difference.
* RSS per process node: VmRSS (/proc/PID/status) of each process the app started, from the
  ``process PID`` locations of ``GET /api/nodes``: in an app with ``--node-processes all`` (the
  lab's rocket nodes as processes of the lab's runner) and, in the first app, the student's
  keyboard manager and the ``--publishers`` nodes below.
* app CPU with process nodes publishing: in the first app, utime+stime of the app's process over
  ``--cpu-window-s`` with none of ``benchpub``'s nodes, then with ``--publishers`` of them started
  by ``POST /api/run`` each publishing std_msgs/Int64 at ``--publish-hz`` on its own topic (the app
  subscribed to each through ``GET /api/hz``, which also reports the rate it sees), then with
  them stopped again (``DELETE /api/launches/ID``): none, with, none. Reported as a percentage of
  one core, and the publishers' own CPU and RSS.

Prints the machine (bench/machine.py) and one JSON object with the results, also written to\nbench/results/process_nodes.json.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import textwrap
import time
from pathlib import Path
from typing import Any

import httpx

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))  # run as a script from anywhere: the app's packages live at the root

from live_server import FrameReader, LiveServer, end, free_port, rss_mib
from machine import machine_info, save_results
from zenoh_graph import POLL_S, cpu_seconds, percentile, wait_until

EXAMPLES = REPO / "examples" / "workspace"
PUBLISHER_FILE = """
import rclpy
from rclpy.node import Node
from std_msgs.msg import Int64


class BenchPublisher(Node):
    def __init__(self):
        super().__init__('bench_publisher')
        self.rate_hz = self.declare_parameter('rate_hz', 20.0).value
        self.pub = self.create_publisher(Int64, '/' + self.get_name() + '/count', 10)
        self.count = 0
        self.create_timer(1.0 / self.rate_hz, self.tick)

    def tick(self):
        self.count += 1
        self.pub.publish(Int64(data=self.count))


if __name__ == '__main__':
    rclpy.init()
    try:
        rclpy.spin(BenchPublisher())
    except KeyboardInterrupt:
        pass
    finally:
        rclpy.try_shutdown()
"""
REFLEX_FILE = """
import rclpy
from keyboard_msgs.msg import Key
from rclpy.node import Node
from std_msgs.msg import Int64


class Reflex(Node):
    \"\"\"Answers every /keydown at once, in its callback, on /bench_reflex.\"\"\"

    def __init__(self):
        super().__init__('bench_reflex')
        self.pub = self.create_publisher(Int64, '/bench_reflex', 10)
        self.create_subscription(Key, '/keydown', self.on_key, 10)

    def on_key(self, msg):
        self.pub.publish(Int64(data=msg.code))


if __name__ == '__main__':
    rclpy.init()
    try:
        rclpy.spin(Reflex())
    except KeyboardInterrupt:
        pass
    finally:
        rclpy.try_shutdown()
"""
REFLEX_KEY = "x"  # no node of the rocket launch acts on it
APPEAR_TIMEOUT_S = 30.0
LEAVE_TIMEOUT_S = 15.0
FRESH_TIMEOUT_S = 30.0
ABORT_TIMEOUT_S = 5.0
RUN_STOP_TIMEOUT_S = 15.0


def get(server: LiveServer, path: str, **params: Any) -> Any:
    response = httpx.get(server.url + path, params=params, timeout=10.0)
    response.raise_for_status()
    return response.json()


def node_list(server: LiveServer) -> list[dict[str, Any]]:
    return list(get(server, "/api/nodes"))


def listed(server: LiveServer, name: str) -> bool:
    return any(n["name"] == name for n in node_list(server))


def process_pids(server: LiveServer) -> dict[str, int]:
    """Node name → pid of every process node the app started (``process PID`` locations)."""
    out: dict[str, int] = {}
    for n in node_list(server):
        location = str(n["location"])
        if location.startswith("process ") and n.get("state") != "died":
            out[n["name"]] = int(location.split()[1])
    return out


def stats_ms(values: list[float]) -> dict[str, Any]:
    ordered = sorted(values)
    if not ordered:
        return {"n": 0}
    return {
        "n": len(ordered),
        "p50_ms": round(percentile(ordered, 0.5), 2),
        "p99_ms": round(percentile(ordered, 0.99), 2),
        "min_ms": round(ordered[0], 2),
        "max_ms": round(ordered[-1], 2),
    }


def make_workspace(root: Path) -> Path:
    workspace = root / "workspace"
    shutil.copytree(EXAMPLES, workspace)
    package = workspace / "src" / "benchpub"
    package.mkdir(parents=True)
    (package / "publisher.py").write_text(textwrap.dedent(PUBLISHER_FILE).lstrip())
    (package / "reflex.py").write_text(textwrap.dedent(REFLEX_FILE).lstrip())
    return workspace


def start_app(root: Path, name: str, *args: str) -> LiveServer:
    workdir = root / name
    workdir.mkdir()
    return LiveServer(workdir, "rocket", "--foxglove-port", str(free_port()), *args)


# -- a: ros2lab run ----------------------------------------------------------------------------
def ros2lab_run(server: LiveServer, root: Path, tries: int) -> dict[str, Any]:
    name = "/KeyboardManagerNode"
    listed_s: list[float] = []
    unlisted_s: list[float] = []
    exit_codes: list[int | None] = []
    for _ in range(tries):
        t0 = time.monotonic()
        proc = subprocess.Popen(
            [sys.executable, "-m", "server", "--url", server.url, "run", "rocketship", "keyboard_manager.py"],
            cwd=root,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            text=True,
        )
        try:
            if not wait_until(lambda: listed(server, name), APPEAR_TIMEOUT_S):
                raise RuntimeError(f"{name} did not appear within {APPEAR_TIMEOUT_S} s")
            listed_s.append(time.monotonic() - t0)
            t_int = time.monotonic()
            proc.send_signal(signal.SIGINT)  # ros2lab passes it on to the node's process
            if wait_until(lambda: not listed(server, name), LEAVE_TIMEOUT_S):
                unlisted_s.append(time.monotonic() - t_int)
            try:
                exit_codes.append(proc.wait(timeout=RUN_STOP_TIMEOUT_S))
            except subprocess.TimeoutExpired:
                exit_codes.append(None)
        finally:
            end(proc)
        time.sleep(0.2)
    return {
        "tries": tries,
        "poll_s": POLL_S,
        "listed_s_median": round(statistics.median(listed_s), 3),
        "listed_s_max": round(max(listed_s), 3),
        "listed_s": [round(v, 3) for v in listed_s],
        "ctrl_c_to_unlisted_s_median": round(statistics.median(unlisted_s), 3) if unlisted_s else None,
        "exit_codes": exit_codes,
    }


# -- b: keydown → abort ------------------------------------------------------------------------
class AbortRig:
    """One app's key channel and echo of /abort_takeoff: (monotonic ns here, data, app's received s)."""

    def __init__(self, server: LiveServer) -> None:
        from websockets.sync.client import connect

        self.server = server
        self.keys = connect(f"{server.ws_url}/ws/keys")
        self.echo = FrameReader(f"{server.ws_url}/ws/topics/abort_takeoff?type=std_msgs/msg/Bool")
        self.latency_ms: list[float] = []
        self.app_callback_ms: list[float] = []
        self.reset_to_fresh_s: list[float] = []
        self.misses = 0

    def snapshot(self) -> list[tuple[int, bool, float]]:
        return [(mono, bool(f["msg"]["data"]), float(f["received"])) for _, mono, f in self.echo.frames()]

    def press(self) -> None:
        self.keys.send(json.dumps({"type": "keydown", "key": "a"}))
        self.keys.send(json.dumps({"type": "keyup", "key": "a"}))

    def prime(self) -> None:
        """Press until the manager aborts once (its /keydown route may take a moment at first)."""
        deadline = time.monotonic() + FRESH_TIMEOUT_S
        while time.monotonic() < deadline:
            self.press()
            if wait_until(lambda: any(d for _, d, _ in self.snapshot()), 1.0):
                return
        raise RuntimeError("the keyboard manager never aborted")

    def _fresh(self, since: int, settle_ns: int) -> bool:
        frames = self.snapshot()[since:]
        first_false = next((i for i, (_, d, _) in enumerate(frames) if not d), None)
        if first_false is None:
            return False
        after = frames[first_false:]
        if any(d for _, d, _ in after):
            return False
        last_true = max((t for t, d, _ in frames if d), default=0)
        return time.monotonic_ns() - max(after[0][0], last_true) >= settle_ns

    def sample(self, settle_s: float) -> None:
        since = len(self.snapshot())
        t_reset = time.monotonic()
        httpx.post(f"{self.server.url}/api/rocket/reset", timeout=30.0).raise_for_status()
        if not wait_until(lambda: self._fresh(since, int(settle_s * 1e9)), FRESH_TIMEOUT_S):
            raise RuntimeError("no fresh keyboard manager after the reset")
        self.reset_to_fresh_s.append(time.monotonic() - t_reset - settle_s)
        before = len(self.snapshot())
        sent_ns, sent_wall = time.monotonic_ns(), time.time()
        self.press()
        if not wait_until(lambda: any(d for _, d, _ in self.snapshot()[before:]), ABORT_TIMEOUT_S):
            self.misses += 1
            return
        here_ns, _, received = next(f for f in self.snapshot()[before:] if f[1])
        self.latency_ms.append((here_ns - sent_ns) / 1e6)
        self.app_callback_ms.append((received - sent_wall) * 1e3)

    def result(self) -> dict[str, Any]:
        return {
            "key_to_abort_frame": stats_ms(self.latency_ms),
            "app_callback": stats_ms(self.app_callback_ms),
            "reset_to_fresh_s_median": round(statistics.median(self.reset_to_fresh_s), 3)
            if self.reset_to_fresh_s
            else None,
            "misses": self.misses,
        }

    def close(self) -> None:
        self.keys.close()
        self.echo.close()


def key_to_abort(
    process_app: LiveServer, inprocess_app: LiveServer, samples: int, settle_s: float
) -> dict[str, Any]:
    km = next((n for n in node_list(process_app) if n["name"] == "/KeyboardManager"), None)
    assert km is not None and str(km["location"]).startswith("process "), f"not a process node: {km}"
    km_in = next((n for n in node_list(inprocess_app) if n["name"] == "/KeyboardManager"), None)
    assert km_in is not None and km_in["location"] == "app", f"not in the app: {km_in}"
    rigs = {"process": AbortRig(process_app), "in_process": AbortRig(inprocess_app)}
    try:
        for rig in rigs.values():
            rig.prime()
        for _ in range(samples):
            for rig in rigs.values():
                rig.sample(settle_s)
        result: dict[str, Any] = {"samples": samples, "settle_s": settle_s}
        for name, rig in rigs.items():
            result[name] = rig.result()
    finally:
        for rig in rigs.values():
            rig.close()
    p, q = result["process"]["key_to_abort_frame"], result["in_process"]["key_to_abort_frame"]
    if p.get("n") and q.get("n"):
        result["process_minus_in_process_p50_ms"] = round(p["p50_ms"] - q["p50_ms"], 2)
    return result


class EchoStamps(FrameReader):
    """An echo WebSocket: the ``received`` stamp (the app's clock, in its subscription callback)
    of each frame, in arrival order."""

    def __init__(self, server: LiveServer, topic: str, type_name: str) -> None:
        super().__init__(f"{server.ws_url}/ws/topics{topic}?type={type_name}&queue_length=100")

    def at(self, index: int) -> float:
        return float(self.frames(index)[0][2]["received"])


def reflex(server: LiveServer, samples: int, gap_s: float) -> dict[str, Any]:
    """/keydown published by the app → a process node's callback → its /bench_reflex back in the
    app. A key frame is sent on /ws/keys; two echo sockets stamp, in the app's callbacks on its
    clock, when /keydown was published in the app and when the node's answer arrived. Their
    difference is the round trip through the node's process (Zenoh both ways, the node's
    executor, CDR both ways); the key frame's own way into the app is reported apart."""
    from websockets.sync.client import connect

    response = httpx.post(
        f"{server.url}/api/run", json={"package": "benchpub", "executable": "reflex.py"}, timeout=30.0
    )
    response.raise_for_status()
    group = response.json()["id"]
    keydown = EchoStamps(server, "/keydown", "keyboard_msgs/msg/Key")
    answer = EchoStamps(server, "/bench_reflex", "std_msgs/msg/Int64")
    keys = connect(f"{server.ws_url}/ws/keys")
    round_trip: list[float] = []
    key_in: list[float] = []
    misses = 0
    try:
        if not wait_until(lambda: listed(server, "/bench_reflex"), APPEAR_TIMEOUT_S):
            raise RuntimeError("the reflex node did not appear")

        def press() -> float:
            sent = time.time()
            keys.send(json.dumps({"type": "keydown", "key": REFLEX_KEY}))
            keys.send(json.dumps({"type": "keyup", "key": REFLEX_KEY}))
            return sent

        deadline = time.monotonic() + FRESH_TIMEOUT_S  # until the node's route is in place
        while answer.count() == 0 and time.monotonic() < deadline:
            press()
            wait_until(lambda: answer.count() > 0, 0.5)
        if answer.count() == 0:
            raise RuntimeError("the reflex node never answered")
        time.sleep(1.0)
        for _ in range(samples):
            k0, a0 = keydown.count(), answer.count()
            sent = press()
            if not wait_until(lambda k=k0, a=a0: keydown.count() > k and answer.count() > a, ABORT_TIMEOUT_S):
                misses += 1
                continue
            round_trip.append((answer.at(a0) - keydown.at(k0)) * 1e3)
            key_in.append((keydown.at(k0) - sent) * 1e3)
            time.sleep(gap_s)
    finally:
        keys.close()
        keydown.close()
        answer.close()
        httpx.delete(f"{server.url}/api/launches/{group}", timeout=30.0)
    return {
        "samples": samples,
        "gap_s": gap_s,
        "misses": misses,
        "keydown_to_answer_in_app": stats_ms(round_trip),
        "key_frame_to_keydown_in_app": stats_ms(key_in),
    }


# -- c: RSS and CPU ----------------------------------------------------------------------------
def rss_of(pids: dict[str, int]) -> dict[str, float]:
    out = {}
    for name, pid in sorted(pids.items()):
        try:
            out[name] = round(rss_mib(pid), 1)
        except (OSError, RuntimeError):
            continue
    return out


def rss_all_processes(root: Path) -> dict[str, Any]:
    """An app with ``--node-processes all`` (the lab's own nodes): each process node's VmRSS."""
    server = start_app(
        root,
        "all_processes",
        "--node-processes",
        "all",
        "--workspace",
        str(root / "no_workspace"),
        "start_delay:=3600",
    )
    try:
        seen: dict[str, int] = {}
        stable_since = time.monotonic()
        deadline = time.monotonic() + APPEAR_TIMEOUT_S
        while time.monotonic() < deadline:
            now = process_pids(server)
            if now != seen:
                seen, stable_since = now, time.monotonic()
            elif seen and time.monotonic() - stable_since > 3.0:
                break
            time.sleep(0.2)
        time.sleep(2.0)  # past their start-up
        rss = rss_of(process_pids(server))
        return {
            "rss_mib": rss,
            "median_mib": round(statistics.median(rss.values()), 1) if rss else None,
            "app_rss_mib": round(server.rss_mib(), 1),
        }
    finally:
        server.stop()


def cpu_window(
    server: LiveServer, seconds: float, topics: list[str], extra_pids: dict[str, int]
) -> dict[str, Any]:
    """The app's CPU % over ``seconds``; ``topics`` asked for their rate at the start and midway."""

    def ask() -> None:
        for topic in topics:
            get(server, f"/api/hz{topic}", window=20)
        if not topics:
            get(server, "/api/health")

    pids = {"app": server.proc.pid, **extra_pids}
    ask()
    before = {k: cpu_seconds(p) for k, p in pids.items()}
    t0 = time.monotonic()
    time.sleep(seconds / 2)
    ask()
    time.sleep(max(0.0, seconds - (time.monotonic() - t0)))
    wall = time.monotonic() - t0
    cpu = {k: round(100.0 * (cpu_seconds(p) - before[k]) / wall, 2) for k, p in pids.items()}
    out: dict[str, Any] = {"app_cpu_pct": cpu.pop("app"), "window_s": round(wall, 2)}
    if cpu:
        out["publisher_cpu_pct"] = cpu
        out["rates_hz_seen_by_app"] = {
            t: round(get(server, f"/api/hz{t}", window=20)["rate_hz"], 2) for t in topics
        }
    return out


def publishers_cpu(server: LiveServer, count: int, hz: float, window_s: float) -> dict[str, Any]:
    names = [f"bench_pub_{i}" for i in range(1, count + 1)]
    topics = [f"/{n}/count" for n in names]
    result: dict[str, Any] = {"publishers": count, "publish_hz": hz}
    result["none_before"] = cpu_window(server, window_s, [], {})
    groups: list[str] = []
    try:
        for name in names:
            response = httpx.post(
                f"{server.url}/api/run",
                json={
                    "package": "benchpub",
                    "executable": "publisher.py",
                    "name": name,
                    "parameters": {"rate_hz": hz},
                },
                timeout=30.0,
            )
            response.raise_for_status()
            groups.append(response.json()["id"])
        if not wait_until(lambda: all(f"/{n}" in process_pids(server) for n in names), APPEAR_TIMEOUT_S):
            raise RuntimeError("the publishers did not all appear")
        pids = {f"/{n}": process_pids(server)[f"/{n}"] for n in names}
        for topic in topics:  # the app subscribes (its topic watch), then rates settle
            wait_until(
                lambda t=topic: any(x["name"] == t for x in get(server, "/api/topics")), APPEAR_TIMEOUT_S
            )
            get(server, f"/api/hz{topic}", window=20)
        time.sleep(2.0)
        result["with_publishers"] = cpu_window(server, window_s, topics, pids)
        result["publisher_rss_mib"] = rss_of(pids)
        result["student_keyboard_manager_rss_mib"] = rss_of(
            {k: v for k, v in process_pids(server).items() if k == "/KeyboardManager"}
        )
    finally:
        for group in groups:
            httpx.delete(f"{server.url}/api/launches/{group}", timeout=30.0)
    wait_until(lambda: not any(f"/{n}" in process_pids(server) for n in names), LEAVE_TIMEOUT_S)
    time.sleep(1.0)
    result["none_after"] = cpu_window(server, window_s, [], {})
    none = (result["none_before"]["app_cpu_pct"] + result["none_after"]["app_cpu_pct"]) / 2
    result["app_cpu_pct_added_by_publishers"] = round(result["with_publishers"]["app_cpu_pct"] - none, 2)
    return result


# -- main --------------------------------------------------------------------------------------
def parse_args(argv: list[str] | None = None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--run-tries", type=int, default=5, help="ros2lab run samples (5)")
    parser.add_argument("--abort-samples", type=int, default=30, help="key → abort samples per app (30)")
    parser.add_argument("--settle-s", type=float, default=0.5, help="quiet wait for a fresh manager (0.5)")
    parser.add_argument(
        "--reflex-samples", type=int, default=200, help="/keydown → reflex node samples (200)"
    )
    parser.add_argument("--cpu-window-s", type=float, default=20.0, help="each CPU window (20)")
    parser.add_argument("--publishers", type=int, default=5, help="publishing process nodes (5)")
    parser.add_argument("--publish-hz", type=float, default=20.0, help="their rate (20)")
    parser.add_argument(
        "--skip", action="append", default=[], choices=["run", "abort", "reflex", "rss", "cpu"]
    )
    return parser.parse_args(argv)


def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)
    machine = machine_info()
    print("machine:", json.dumps(machine), flush=True)
    started = time.monotonic()
    results: dict[str, Any] = {"bench": "process_nodes", "machine": machine}
    with tempfile.TemporaryDirectory(prefix="process_nodes_") as tmp:
        root = Path(tmp)
        workspace = make_workspace(root)
        apps: list[LiveServer] = []
        try:
            student = start_app(root, "student", "--workspace", str(workspace), "start_delay:=3600")
            apps.append(student)
            if "run" not in args.skip:
                results["ros2lab_run"] = ros2lab_run(student, root, args.run_tries)
                print("ros2lab_run:", json.dumps(results["ros2lab_run"]), flush=True)
            if "abort" not in args.skip:
                inprocess = start_app(
                    root, "in_process", "--workspace", str(root / "no_workspace"), "start_delay:=3600"
                )
                apps.append(inprocess)
                results["key_to_abort"] = key_to_abort(student, inprocess, args.abort_samples, args.settle_s)
                print("key_to_abort:", json.dumps(results["key_to_abort"]), flush=True)
                inprocess.stop()
                apps.remove(inprocess)
            if "reflex" not in args.skip:
                results["reflex"] = reflex(student, args.reflex_samples, 0.05)
                print("reflex:", json.dumps(results["reflex"]), flush=True)
            if "cpu" not in args.skip:
                results["publishers_cpu"] = publishers_cpu(
                    student, args.publishers, args.publish_hz, args.cpu_window_s
                )
                print("publishers_cpu:", json.dumps(results["publishers_cpu"]), flush=True)
            results["app_log_problems"] = student.log_problems()[-20:]
            student.stop()
            apps.remove(student)
            if "rss" not in args.skip:
                results["rss_node_processes_all"] = rss_all_processes(root)
                print("rss_node_processes_all:", json.dumps(results["rss_node_processes_all"]), flush=True)
        finally:
            for app in apps:
                app.stop()
    results["load_average_at_end"] = os.getloadavg()
    results["wall_s"] = round(time.monotonic() - started, 1)
    print(json.dumps(results, indent=2))
    save_results("process_nodes", results)
    return 0


if __name__ == "__main__":
    sys.exit(main())
