"""Bench: the lab's ROS graph on Zenoh, measured from outside the app.

    .venv/bin/python bench/zenoh_graph.py [--rate-s 20] [--flat-s 5] [--idle-s 15] [--idle-rounds 2]
                                          [--discovery-tries 5]

Everything runs on loopback: every app and Zenoh session binds 127.0.0.1 on a free port with
multicast scouting off; every child process is ended by its own pid. What is measured:

* idle cost: two real apps started side by side and measured over the same windows, so the
  machine's load hits both alike: ``python -m server --launch rocket start_delay:=3600`` with its
  Zenoh router on a free port and no peer, and the same with ``--no-zenoh``. After ``--idle-warmup-s``,
  ``--idle-rounds`` windows of ``--idle-s``: utime+stime of the app's process (all its threads,
  /proc/PID/stat) as a percentage of one core, and VmRSS at each window's end; medians reported.
  (start_delay:=3600 keeps the rocket on its pad, so both apps idle in the same state.)
* latency and throughput, "publish in another process -> callback in the app": the app with
  Zenoh on, an echo WebSocket (``/ws/topics/bench_chatter?type=std_msgs/msg/String``) that makes
  the app's subscription, and a child process using this project's rclpy (a peer session
  connected to the app's router, as a student's node) publishing std_msgs/msg/String whose text
  carries the send time, ``time.time_ns()`` taken just before ``publish()``. The receive time is
  the ``received`` field of the echo frame: the app's bus clock read inside the subscription's
  callback (``EchoNode.on_message``, on the app's executor), so the WebSocket leg back to this
  bench is not counted (it is reported apart as ``to_ws_client``). Clocks: CLOCK_REALTIME in the
  publisher; the app's SystemClock is CLOCK_MONOTONIC plus the realtime offset taken at its
  start, equal to CLOCK_REALTIME unless the wall clock was stepped (the result reports the
  drift of realtime-minus-monotonic over the run; it should be ~0). Two runs, each after
  ``--warmup-s`` at 50 Hz that is not counted (routes and matching settle): 50 Hz for ``--rate-s``,
  and flat out (a tight publish loop) for ``--flat-s``. ``msgs_per_s`` is messages whose callback
  ran in the app (echo frames plus the echo's own drop count) over first publish to last callback.
  Flat out, the app is the bottleneck: its Zenoh inbox keeps the newest samples per topic (as many
  as the deepest subscription, here the echo's 1000) and drops older ones (``lost``), latency is
  then mostly queueing, and the echo's sending to this bench runs on the app's event loop too.
  ``app_bridge_received`` is the app's own count (``/api/health``) of samples it decoded.
* the same exchange between two plain ``eclipse-zenoh`` processes in the same run, interleaved
  with the app's: a router (as the app is) with a subscriber whose callback stamps
  ``time.time_ns()`` on Zenoh's thread, and a peer (as a node process is) putting the same payload
  bytes (a CDR std_msgs/String of the same length) with the same congestion control (drop) and
  reliability, no attachment. ``ratio_app_over_bare`` divides the app's figures by these.
* discovery: from just before ``Popen`` of ``python FILE`` (a minimal node written with this
  project's rclpy, the router given by ``ZENOH_CONFIG_OVERRIDE`` as the app gives it) until its
  name is in the app's ``GET /api/nodes`` (polled every 20 ms): ``listed_s``, median over
  ``--discovery-tries``. The node's own stamps (CLOCK_REALTIME, as the bench's) place, from the
  same instant, when the file starts to run (``file_runs_s``), when ``rclpy.init()`` returns
  (``init_done_s``: imports, the router found, the graph settled) and when ``Node(...)`` returns
  (``node_made_s``; the node's token is declared inside the constructor, so it can be listed
  before that). Also the time from Ctrl-C (SIGINT to its pid) until it leaves the list.

Prints the machine (bench/machine.py) and one JSON object with the results, also written to\nbench/results/zenoh_graph.json.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import select
import signal
import statistics
import struct
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))  # run as a script from anywhere: the app's packages live at the root

from live_server import FrameReader, LiveServer, cpu_s, end, free_port, rss_mib
from machine import machine_info, save_results

TOPIC = "/bench_chatter"
BARE_KEY = "bench/chatter"
PAYLOAD_CHARS = 40  # "<phase> <seq> <time_ns>" padded: CDR string of 4 + 4 + 41 bytes
WARMUP_HZ = 50.0
POLL_S = 0.02
CHILD_GRACE_S = 60.0
QUIET_S = 0.5  # no new frame for this long: the exchange is over
DRAIN_LIMIT_S = 15.0
LEAVE_TIMEOUT_S = 15.0
APPEAR_TIMEOUT_S = 30.0
STOP_TIMEOUT_S = 10.0


# -- shared by the parent and the children ---------------------------------------------------
def stamp_text(phase: str, seq: int, t_ns: int) -> str:
    return f"{phase} {seq:09d} {t_ns:019d}".ljust(PAYLOAD_CHARS)


def parse_text(text: str) -> tuple[str, int, int]:
    phase, seq, t_ns = text.split()[:3]
    return phase, int(seq), int(t_ns)


def cdr_string(text: str) -> bytes:
    """A std_msgs/msg/String in little-endian CDR, as rmw_zenoh puts it on the wire."""
    data = text.encode() + b"\x00"
    return b"\x00\x01\x00\x00" + struct.pack("<I", len(data)) + data


def publish_loop(
    send: Callable[[str], None], rate_hz: float, duration_s: float, warmup_s: float
) -> dict[str, Any]:
    """Warm-up at 50 Hz (phase ``w``), then ``rate_hz`` (0: flat out) for ``duration_s`` (phase ``m``)."""
    sent = {"w": 0, "m": 0}
    spans: dict[str, float] = {}
    seq = 0
    for phase, length, hz in (("w", warmup_s, WARMUP_HZ), ("m", duration_s, rate_hz)):
        period = 1.0 / hz if hz > 0 else 0.0
        start = time.monotonic()
        due, end = start, start + length
        while True:
            now = time.monotonic()
            if now >= end:
                break
            if period:
                if now < due:
                    time.sleep(min(due - now, end - now))
                    continue
                due += period
            seq += 1
            send(stamp_text(phase, seq, time.time_ns()))
            sent[phase] += 1
        spans[phase] = time.monotonic() - start
    return {"sent_warmup": sent["w"], "sent": sent["m"], "publish_s": round(spans["m"], 3)}


def percentile(ordered: list[float], q: float) -> float:
    """Nearest rank on a sorted list."""
    return ordered[min(len(ordered) - 1, max(0, round(q * len(ordered)) - 1))]


def summarize(rows: list[tuple[int, int, int]]) -> dict[str, Any]:
    """(seq, sent ns, received ns) of the measured phase → count, latency percentiles, rate."""
    if not rows:
        return {"received": 0}
    lat = sorted((recv - sent) / 1e6 for _, sent, recv in rows)
    first_sent = min(sent for _, sent, _ in rows)
    last_recv = max(recv for _, _, recv in rows)
    span_s = max(1e-9, (last_recv - first_sent) / 1e9)
    return {
        "received": len(rows),
        "p50_ms": round(percentile(lat, 0.50), 3),
        "p99_ms": round(percentile(lat, 0.99), 3),
        "max_ms": round(lat[-1], 3),
        "min_ms": round(lat[0], 3),
        "msgs_per_s": round(len(rows) / span_s, 1),
    }


def zenoh_config(mode: str, listen: list[str], connect: list[str]) -> Any:
    import zenoh

    config = zenoh.Config()
    config.insert_json5("mode", json.dumps(mode))
    config.insert_json5("scouting/multicast/enabled", "false")
    config.insert_json5("listen/endpoints", json.dumps(listen))
    config.insert_json5("connect/endpoints", json.dumps(connect))
    return config


# -- the children (``--role``) -----------------------------------------------------------------
def role_rclpy_pub(args: argparse.Namespace) -> int:
    """A node process with this project's rclpy: the router comes from ZENOH_CONFIG_OVERRIDE."""
    import rclpy
    from rclpy.node import Node
    from std_msgs.msg import String

    rclpy.init(args=["bench_pub"])
    node = Node("bench_pub")
    pub = node.create_publisher(String, TOPIC, 10)
    result = publish_loop(lambda text: pub.publish(String(data=text)), args.rate, args.duration, args.warmup)
    bridge = rclpy.get_default_context().bridge
    result["zenoh_puts"] = bridge.stats.sent if bridge is not None else None
    print(json.dumps(result), flush=True)
    node.destroy_node()
    rclpy.shutdown()
    return 0


def role_bare_pub(args: argparse.Namespace) -> int:
    import zenoh

    session = zenoh.open(zenoh_config("peer", ["tcp/127.0.0.1:0"], [args.connect]))
    try:
        pub = session.declare_publisher(
            BARE_KEY, congestion_control=zenoh.CongestionControl.DROP, reliability=zenoh.Reliability.RELIABLE
        )
        result = publish_loop(lambda text: pub.put(cdr_string(text)), args.rate, args.duration, args.warmup)
        print(json.dumps(result), flush=True)
        pub.undeclare()
    finally:
        session.close()
    return 0


def role_bare_sub(args: argparse.Namespace) -> int:
    """A router with one subscriber; says ``ready``, and its summary once ``stop`` comes on stdin."""
    import zenoh

    got: list[tuple[int, bytes]] = []

    def on_sample(sample: zenoh.Sample) -> None:
        got.append((time.time_ns(), sample.payload.to_bytes()))

    session = zenoh.open(zenoh_config("router", [args.listen], []))
    try:
        sub = session.declare_subscriber(BARE_KEY, on_sample)
        print(json.dumps({"event": "ready"}), flush=True)
        deadline = time.monotonic() + args.max_s
        while time.monotonic() < deadline:
            ready, _, _ = select.select([sys.stdin], [], [], 0.5)
            if ready and sys.stdin.readline().strip() in ("stop", ""):
                break
        sub.undeclare()
        rows = []
        for recv_ns, payload in list(got):
            phase, seq, sent_ns = parse_text(payload[8:-1].decode())
            if phase == "m":
                rows.append((seq, sent_ns, recv_ns))
        print(
            json.dumps(
                {"event": "summary", **summarize(rows), "payload_bytes": len(got[-1][1]) if got else 0}
            )
        )
    finally:
        session.close()
    return 0


# -- the parent: helpers -----------------------------------------------------------------------
def child_env(router: str) -> dict[str, str]:
    return {**os.environ, "ZENOH_CONFIG_OVERRIDE": f'connect/endpoints=["{router}"]', "PYTHONUNBUFFERED": "1"}


def read_json_line(proc: subprocess.Popen[str], timeout_s: float) -> dict[str, Any]:
    """The next JSON line of the child's stdout, within ``timeout_s``."""
    assert proc.stdout is not None
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        ready, _, _ = select.select([proc.stdout], [], [], 0.2)
        if ready:
            line = proc.stdout.readline()
            if not line:
                break
            with contextlib.suppress(json.JSONDecodeError):
                return dict(json.loads(line))
    raise RuntimeError(f"no JSON line from pid {proc.pid} within {timeout_s} s")


def ratio(a: float | None, b: float | None) -> float | None:
    return round(a / b, 2) if a is not None and b else None


def median(values: list[float]) -> float | None:
    return round(statistics.median(values), 3) if values else None


def nodes(server: LiveServer) -> set[str]:
    import httpx

    return {n["name"] for n in httpx.get(f"{server.url}/api/nodes", timeout=5.0).json()}


def health(server: LiveServer) -> dict[str, Any]:
    import httpx

    return dict(httpx.get(f"{server.url}/api/health", timeout=5.0).json())


# -- b: idle cost ------------------------------------------------------------------------------
def idle_cost(root: Path, warmup_s: float, idle_s: float, rounds: int) -> tuple[dict[str, Any], LiveServer]:
    """Both apps side by side; the Zenoh one is returned still running, for the other parts."""
    servers: dict[str, LiveServer] = {}
    for name, extra in (("zenoh", []), ("no_zenoh", ["--no-zenoh"])):
        (root / name).mkdir()
        servers[name] = LiveServer(
            root / name, "rocket", "--foxglove-port", str(free_port()), *extra, "start_delay:=3600"
        )
    try:
        assert health(servers["zenoh"])["zenoh"] is not None, "the Zenoh app has no Zenoh session"
        assert health(servers["no_zenoh"])["zenoh"] is None, "the --no-zenoh app has a Zenoh session"
        time.sleep(warmup_s)
        cpu: dict[str, list[float]] = {k: [] for k in servers}
        rss: dict[str, list[float]] = {k: [] for k in servers}
        for _ in range(rounds):
            before = {k: cpu_s(s.proc.pid) for k, s in servers.items()}
            t0 = time.monotonic()
            time.sleep(idle_s)
            wall = time.monotonic() - t0
            for k, s in servers.items():
                cpu[k].append(100.0 * (cpu_s(s.proc.pid) - before[k]) / wall)
                rss[k].append(rss_mib(s.proc.pid))
        result: dict[str, Any] = {"window_s": idle_s, "rounds": rounds, "warmup_s": warmup_s}
        for k in servers:
            result[k] = {
                "cpu_pct_median": median(cpu[k]),
                "cpu_pct_rounds": [round(v, 2) for v in cpu[k]],
                "rss_mib_median": median(rss[k]),
                "rss_mib_rounds": [round(v, 1) for v in rss[k]],
            }
        result["cpu_pct_zenoh_minus_no_zenoh"] = round(
            result["zenoh"]["cpu_pct_median"] - result["no_zenoh"]["cpu_pct_median"], 2
        )
        result["rss_mib_zenoh_minus_no_zenoh"] = round(
            result["zenoh"]["rss_mib_median"] - result["no_zenoh"]["rss_mib_median"], 1
        )
    except BaseException:
        for s in servers.values():
            s.stop()
        raise
    servers["no_zenoh"].stop()
    return result, servers["zenoh"]


# -- a: latency and throughput -----------------------------------------------------------------
class EchoReader(FrameReader):
    """The app's echo WebSocket on TOPIC, read on a thread."""

    def __init__(self, server: LiveServer) -> None:
        super().__init__(f"{server.ws_url}/ws/topics{TOPIC}?type=std_msgs/msg/String&queue_length=1000")

    def wait_quiet(self) -> None:
        deadline = time.monotonic() + DRAIN_LIMIT_S
        while time.monotonic() < deadline and time.monotonic_ns() - self.last_monotonic_ns < QUIET_S * 1e9:
            time.sleep(0.05)


def exchange_app(server: LiveServer, rate_hz: float, duration_s: float, warmup_s: float) -> dict[str, Any]:
    reader = EchoReader(server)
    received_before = health(server)["zenoh"]["received"]
    router = f"tcp/127.0.0.1:{server.zenoh_port}"
    child = subprocess.Popen(
        [
            sys.executable,
            __file__,
            "--role",
            "rclpy-pub",
            "--rate",
            str(rate_hz),
            "--duration",
            str(duration_s),
            "--warmup",
            str(warmup_s),
        ],
        env=child_env(router),
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        out, err = child.communicate(timeout=duration_s + warmup_s + CHILD_GRACE_S)
    except subprocess.TimeoutExpired:
        end(child)
        reader.close()
        raise RuntimeError("the rclpy publisher did not finish in time") from None
    reader.wait_quiet()
    reader.close()
    if child.returncode != 0:
        raise RuntimeError(f"the rclpy publisher failed ({child.returncode}):\n{err[-2000:]}")
    pub = json.loads(out.strip().splitlines()[-1])
    rows: list[tuple[int, int, int]] = []
    to_client: list[float] = []
    dropped = 0
    for here_ns, _, frame in reader.frames():
        dropped = max(dropped, int(frame.get("dropped", 0)))
        phase, seq, sent_ns = parse_text(frame["msg"]["data"])
        if phase == "m":
            rows.append((seq, sent_ns, round(frame["received"] * 1e9)))
            to_client.append((here_ns - sent_ns) / 1e6)
    result = {"rate_hz": rate_hz or "flat out", **pub, **summarize(rows)}
    result["echo_dropped"] = dropped  # callbacks that ran but whose frame the echo dropped (slow client)
    if dropped and rows:
        span_s = (max(r for _, _, r in rows) - min(s for _, s, _ in rows)) / 1e9
        result["msgs_per_s"] = round((len(rows) + dropped) / max(span_s, 1e-9), 1)
    result["lost"] = pub["sent"] - result.get("received", 0) - dropped
    result["app_bridge_received"] = health(server)["zenoh"]["received"] - received_before
    to_client.sort()
    if to_client:
        result["to_ws_client_p50_ms"] = round(percentile(to_client, 0.5), 3)
        result["to_ws_client_p99_ms"] = round(percentile(to_client, 0.99), 3)
    return result


def exchange_bare(rate_hz: float, duration_s: float, warmup_s: float) -> dict[str, Any]:
    endpoint = f"tcp/127.0.0.1:{free_port()}"
    script = [sys.executable, __file__]
    sub = subprocess.Popen(
        [
            *script,
            "--role",
            "bare-sub",
            "--listen",
            endpoint,
            "--max-s",
            str(duration_s + warmup_s + CHILD_GRACE_S),
        ],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    pub: subprocess.Popen[str] | None = None
    try:
        read_json_line(sub, 30.0)  # ready
        pub = subprocess.Popen(
            [
                *script,
                "--role",
                "bare-pub",
                "--connect",
                endpoint,
                "--rate",
                str(rate_hz),
                "--duration",
                str(duration_s),
                "--warmup",
                str(warmup_s),
            ],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        out, err = pub.communicate(timeout=duration_s + warmup_s + CHILD_GRACE_S)
        if pub.returncode != 0:
            raise RuntimeError(f"the bare publisher failed ({pub.returncode}):\n{err[-2000:]}")
        sent = json.loads(out.strip().splitlines()[-1])
        time.sleep(1.0)  # what is in flight lands
        assert sub.stdin is not None
        sub.stdin.write("stop\n")
        sub.stdin.flush()
        summary = read_json_line(sub, 30.0)
        sub.wait(timeout=STOP_TIMEOUT_S)
    finally:
        if pub is not None:
            end(pub)
        end(sub)
    summary.pop("event", None)
    result = {"rate_hz": rate_hz or "flat out", **sent, **summary}
    result["lost"] = sent["sent"] - summary.get("received", 0)
    return result


def latency_throughput(server: LiveServer, rate_s: float, flat_s: float, warmup_s: float) -> dict[str, Any]:
    from node_runtime.msgs.generated.std_msgs import String
    from node_runtime.msgs.wire import serialize

    text = stamp_text("m", 1, time.time_ns())
    assert serialize(String(data=text)) == cdr_string(text), "the bare payload is not the app's CDR"
    runs: dict[str, Any] = {}
    for name, hz, seconds in (("rate_50hz", 50.0, rate_s), ("flat_out", 0.0, flat_s)):
        app = exchange_app(server, hz, seconds, warmup_s)
        bare = exchange_bare(hz, seconds, warmup_s)
        runs[name] = {
            "app": app,
            "bare_zenoh": bare,
            "ratio_app_over_bare": {
                "p50": ratio(app.get("p50_ms"), bare.get("p50_ms")),
                "p99": ratio(app.get("p99_ms"), bare.get("p99_ms")),
                "msgs_per_s": ratio(app.get("msgs_per_s"), bare.get("msgs_per_s")),
            },
        }
    runs["payload_bytes"] = len(cdr_string(text))
    runs["warmup_s"] = warmup_s
    return runs


# -- c: discovery ------------------------------------------------------------------------------
NODE_FILE = """
import json
import sys
import time

t_start = time.time()
import rclpy
from rclpy.node import Node


def main():
    rclpy.init()
    t_init = time.time()
    node = Node(sys.argv[1])
    print(json.dumps({"file_start": t_start, "init_done": t_init, "node_made": time.time()}), flush=True)
    try:
        rclpy.spin(node)
    except KeyboardInterrupt:
        pass
    finally:
        rclpy.try_shutdown()


if __name__ == '__main__':
    main()
"""


def wait_until(condition: Callable[[], bool], timeout_s: float) -> bool:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if condition():
            return True
        time.sleep(POLL_S)
    return False


def discovery(server: LiveServer, root: Path, tries: int) -> dict[str, Any]:
    node_file = root / "minimal_node.py"
    node_file.write_text(NODE_FILE)
    env = child_env(f"tcp/127.0.0.1:{server.zenoh_port}")
    samples: list[dict[str, float]] = []
    for i in range(tries):
        name = f"bench_discovery_{i}"
        t0 = time.time()
        proc = subprocess.Popen(
            [sys.executable, str(node_file), name],
            env=env,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        try:
            if not wait_until(lambda n=name: f"/{n}" in nodes(server), APPEAR_TIMEOUT_S):
                raise RuntimeError(f"{name} did not appear in /api/nodes within {APPEAR_TIMEOUT_S} s")
            seen = time.time()
            stamps = read_json_line(proc, 10.0)
            t_int = time.time()
            proc.send_signal(signal.SIGINT)
            left = wait_until(lambda n=name: f"/{n}" not in nodes(server), LEAVE_TIMEOUT_S)
            gone = time.time()
        finally:
            end(proc)
        samples.append(
            {
                "listed_s": seen - t0,
                "file_runs_s": stamps["file_start"] - t0,
                "init_done_s": stamps["init_done"] - t0,
                "node_made_s": stamps["node_made"] - t0,
                "ctrl_c_to_unlisted_s": (gone - t_int) if left else float("nan"),
            }
        )
        time.sleep(0.2)
    keys = list(samples[0])
    return {
        "tries": tries,
        "poll_s": POLL_S,
        "median": {k: median([s[k] for s in samples]) for k in keys},
        "max": {k: round(max(s[k] for s in samples), 3) for k in keys},
    }


# -- main --------------------------------------------------------------------------------------
def parse_args(argv: list[str] | None = None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rate-s", type=float, default=20.0, help="seconds of the 50 Hz run (20)")
    parser.add_argument("--flat-s", type=float, default=5.0, help="seconds of the flat-out run (5)")
    parser.add_argument("--warmup-s", type=float, default=2.0, help="50 Hz warm-up before each run (2)")
    parser.add_argument("--idle-s", type=float, default=15.0, help="seconds of each idle window (15)")
    parser.add_argument("--idle-rounds", type=int, default=2, help="idle windows (2)")
    parser.add_argument("--idle-warmup-s", type=float, default=5.0, help="wait after ready before idle (5)")
    parser.add_argument("--discovery-tries", type=int, default=5, help="discovery samples (5)")
    parser.add_argument("--skip", action="append", default=[], choices=["idle", "latency", "discovery"])
    # a child's role (this file runs itself as the publisher and the bare Zenoh processes)
    parser.add_argument("--role", choices=["rclpy-pub", "bare-pub", "bare-sub"], help=argparse.SUPPRESS)
    parser.add_argument("--rate", type=float, default=50.0, help=argparse.SUPPRESS)
    parser.add_argument("--duration", type=float, default=5.0, help=argparse.SUPPRESS)
    parser.add_argument("--warmup", type=float, default=2.0, help=argparse.SUPPRESS)
    parser.add_argument("--listen", help=argparse.SUPPRESS)
    parser.add_argument("--connect", help=argparse.SUPPRESS)
    parser.add_argument("--max-s", type=float, default=120.0, help=argparse.SUPPRESS)
    return parser.parse_args(argv)


def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)
    if args.role == "rclpy-pub":
        return role_rclpy_pub(args)
    if args.role == "bare-pub":
        return role_bare_pub(args)
    if args.role == "bare-sub":
        return role_bare_sub(args)
    machine = machine_info()
    print("machine:", json.dumps(machine), flush=True)
    offset_start = time.time() - time.monotonic()
    started = time.monotonic()
    results: dict[str, Any] = {"bench": "zenoh_graph", "machine": machine}
    with tempfile.TemporaryDirectory(prefix="zenoh_graph_") as tmp:
        root = Path(tmp)
        server: LiveServer | None = None
        try:
            if "idle" in args.skip:
                (root / "zenoh").mkdir()
                server = LiveServer(
                    root / "zenoh", "rocket", "--foxglove-port", str(free_port()), "start_delay:=3600"
                )
            else:
                results["idle"], server = idle_cost(root, args.idle_warmup_s, args.idle_s, args.idle_rounds)
                print("idle:", json.dumps(results["idle"]), flush=True)
            if "latency" not in args.skip:
                results["latency_throughput"] = latency_throughput(
                    server, args.rate_s, args.flat_s, args.warmup_s
                )
                print("latency_throughput:", json.dumps(results["latency_throughput"]), flush=True)
            if "discovery" not in args.skip:
                results["discovery"] = discovery(server, root, args.discovery_tries)
                print("discovery:", json.dumps(results["discovery"]), flush=True)
            results["app_log_problems"] = server.log_problems()[-20:]
        finally:
            if server is not None:
                server.stop()
    results["clock"] = {
        "sent": "CLOCK_REALTIME (time.time_ns) in the publishers",
        "received": "app: its SystemClock (CLOCK_MONOTONIC + realtime offset at start); bare: CLOCK_REALTIME",
        "realtime_minus_monotonic_drift_us": round((time.time() - time.monotonic() - offset_start) * 1e6, 1),
    }
    results["load_average_at_end"] = os.getloadavg()
    results["wall_s"] = round(time.monotonic() - started, 1)
    print(json.dumps(results, indent=2))
    save_results("zenoh_graph", results)
    return 0


if __name__ == "__main__":
    sys.exit(main())
