"""Bench: start-up time, idle CPU and memory of ``python -m server --launch rocket``, and the
server-side latency of a key frame on /ws/keys to the Key message on /keydown.

    .venv/bin/python bench/startup_idle_keys.py [--starts 5] [--idle-s 20] [--presses 1000]

What is measured, exactly:

* start-up: from just before ``subprocess.Popen`` of ``python -m server --launch rocket --port P``
  to the first ``GET /api/health`` answered 200 (polled every 10 ms); the median over ``--starts``
  fresh processes.
* idle CPU: the same command, no browser connected, default launch arguments (the countdown
  starts after 5 s and the rocket launches, so /cmd_vel and /sensor_vel run at 10 Hz and viser's
  view redraws): utime+stime of the process (all threads, ``/proc/<pid>/stat``) over ``--idle-s``
  seconds of wall time right after it is ready, as a percentage of one core.
* memory: VmRSS (``/proc/<pid>/status``) just after ready and after the idle period.
* key latency, in one process: the app from ``create_app(Settings(lab=LabSettings(viewer=False, launch='rocket')))``
  under uvicorn in a thread on a free loopback port, a ``websockets`` client in the main thread
  sending ``{"type": "keydown", "key": "ArrowUp"}`` then a keyup, one press at a time. Three
  instants on ``time.perf_counter`` (one clock, one process), none needing app changes:
    - ``frame``: the app's ASGI ``receive()`` returns the ``websocket.receive`` message (uvicorn has
      read and unmasked the frame; wrapped around the app as ASGI middleware here);
    - ``parsed``: entry to ``lab.keyboard.key_down`` (the frame has been parsed and mapped to an
      SDL code; wrapped on the instance);
    - ``delivered``: a bench subscriber's callback on /keydown runs (the executor delivered the
      Key message the keyboard node published, like any node's subscription).
  Reported: frame → delivered ("key frame received → Key message delivered") and
  parsed → delivered, p50 and p99 over ``--presses`` presses after ``--warmup`` unmeasured ones.
  Not included: the browser, the client's send and the loopback TCP hop.

Results are printed as a table with the machine's details and written as JSON to bench/results/.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import statistics
import subprocess
import sys
import threading
import time
from collections.abc import Callable
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import httpx

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))  # run as a script from anywhere: the app's packages live at the root

from live_server import cpu_s, end, free_port
from machine import machine_info

RESULTS = REPO / "bench" / "results"
READY_TIMEOUT_S = 60.0
STOP_TIMEOUT_S = 10.0
PRESS_TIMEOUT_S = 5.0
AIMS = {"idle_cpu_pct": 5.0, "rss_mb": 150.0, "key_p99_ms": 2.0}  # the aims set for the lab


# -- the machine -----------------------------------------------------------------------------
# -- /proc -----------------------------------------------------------------------------------
def rss_mb(pid: int) -> float:
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024  # kB → MiB
    raise RuntimeError(f"no VmRSS for pid {pid}")


# -- the server as a subprocess --------------------------------------------------------------
class ServerProcess:
    def __init__(self) -> None:
        self.port = free_port()
        self.url = f"http://127.0.0.1:{self.port}"
        self.spawned_at = time.perf_counter()
        self.proc = subprocess.Popen(
            [
                sys.executable,
                "-m",
                "server",
                "--launch",
                "rocket",
                "--host",
                "127.0.0.1",
                "--port",
                str(self.port),
                "--log-level",
                "warning",
            ],
            cwd=REPO,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            text=True,
        )

    def wait_ready(self) -> float:
        """Seconds from spawn to the first /api/health 200."""
        deadline = time.monotonic() + READY_TIMEOUT_S
        with httpx.Client(timeout=1.0) as client:
            while True:
                try:
                    if client.get(f"{self.url}/api/health").status_code == 200:
                        return time.perf_counter() - self.spawned_at
                except httpx.HTTPError:
                    pass
                if self.proc.poll() is not None or time.monotonic() > deadline:
                    self.stop()
                    raise RuntimeError(
                        f"server not ready:\n{self.proc.stderr.read() if self.proc.stderr else ''}"
                    )
                time.sleep(0.01)

    def stop(self) -> None:
        end(self.proc, STOP_TIMEOUT_S)


def bench_startup(starts: int) -> dict[str, Any]:
    times = []
    for _ in range(starts):
        server = ServerProcess()
        try:
            times.append(server.wait_ready())
        finally:
            server.stop()
    return {"startup_s": times, "startup_median_s": statistics.median(times)}


def bench_idle(idle_s: float) -> dict[str, Any]:
    server = ServerProcess()
    try:
        server.wait_ready()
        pid = server.proc.pid
        rss_start = rss_mb(pid)
        cpu0, wall0 = cpu_s(pid), time.monotonic()
        time.sleep(idle_s)  # the measurement window itself
        cpu1, wall1 = cpu_s(pid), time.monotonic()
        rss_end = rss_mb(pid)
        health = httpx.get(f"{server.url}/api/health", timeout=2.0).json()
    finally:
        server.stop()
    return {
        "idle_window_s": wall1 - wall0,
        "idle_cpu_s": cpu1 - cpu0,
        "idle_cpu_pct": 100.0 * (cpu1 - cpu0) / (wall1 - wall0),
        "rss_after_start_mb": rss_start,
        "rss_after_idle_mb": rss_end,
        "nodes": health["nodes"],
        "topics": health["topics"],
    }


# -- key latency, in process -----------------------------------------------------------------
class FrameClock:
    """ASGI middleware: notes when the app receives each WebSocket frame on /ws/keys, and which
    event loop the app runs on (the bus lives there)."""

    def __init__(self, app: Any, stamps: list[float]) -> None:
        self.app = app
        self.stamps = stamps
        self.loop: asyncio.AbstractEventLoop | None = None

    async def __call__(self, scope: Any, receive: Callable[[], Any], send: Any) -> None:
        if scope["type"] == "lifespan":
            self.loop = asyncio.get_running_loop()
        if scope["type"] != "websocket" or scope["path"] != "/ws/keys":
            return await self.app(scope, receive, send)

        async def timed_receive() -> Any:
            message = await receive()
            if message["type"] == "websocket.receive":
                self.stamps.append(time.perf_counter())
            return message

        await self.app(scope, timed_receive, send)


def bench_keys(presses: int, warmup: int) -> dict[str, Any]:
    import uvicorn
    from websockets.sync.client import connect

    from node_runtime.bus import Node
    from node_runtime.msgs import Key
    from server.app import create_app
    from server.host.settings import LabSettings, Listening, Settings

    settings = Settings(lab=LabSettings(viewer=False, launch="rocket"), listen=Listening(port=free_port()))
    app = create_app(settings)
    frames: list[float] = []
    clock = FrameClock(app, frames)
    server = uvicorn.Server(
        uvicorn.Config(
            clock,
            host="127.0.0.1",
            port=settings.listen.port,
            log_level="warning",
            lifespan="on",
            ws_max_size=1 << 20,
        )
    )
    thread = threading.Thread(target=server.run, name="uvicorn", daemon=True)
    thread.start()
    deadline = time.monotonic() + READY_TIMEOUT_S
    while not server.started:
        if time.monotonic() > deadline or not thread.is_alive():
            raise RuntimeError("the in-process server did not start")
        time.sleep(0.01)

    lab = app.state.lab
    parsed: list[float] = []
    delivered: list[float] = []
    arrived = threading.Event()
    original_key_down = lab.keyboard.key_down

    def key_down(*args: Any, **kwargs: Any) -> Any:
        parsed.append(time.perf_counter())
        return original_key_down(*args, **kwargs)

    def on_key(_msg: Any) -> None:
        delivered.append(time.perf_counter())
        arrived.set()

    async def attach() -> Node:  # on the app's loop, where the bus lives
        with lab.bus.activate():
            probe = Node("_bench_probe")
        probe.create_subscription(Key, "/keydown", on_key, 10)
        return probe

    assert clock.loop is not None, "the lifespan ran, so the loop is known"
    asyncio.run_coroutine_threadsafe(attach(), clock.loop).result(timeout=5)
    lab.keyboard.key_down = key_down
    try:
        with connect(f"ws://127.0.0.1:{settings.listen.port}/ws/keys") as ws:
            for _ in range(warmup + presses):
                arrived.clear()
                ws.send(json.dumps({"type": "keydown", "key": "ArrowUp", "code": "ArrowUp"}))
                if not arrived.wait(PRESS_TIMEOUT_S):
                    raise RuntimeError("a keydown never reached /keydown")
                ws.send(json.dumps({"type": "keyup", "key": "ArrowUp", "code": "ArrowUp"}))
    finally:
        server.should_exit = True
        thread.join(timeout=STOP_TIMEOUT_S)

    keydown_frames = frames[0::2]  # keydown, keyup, keydown, ...: the client waits after each keydown
    n = warmup + presses
    if len(keydown_frames) < n or len(parsed) != n or len(delivered) != n:
        raise RuntimeError(
            f"stamps do not line up: {len(keydown_frames)} frames, {len(parsed)} parsed, "
            f"{len(delivered)} delivered for {n} presses"
        )
    frame_ms = [(d - f) * 1000 for f, d in zip(keydown_frames[warmup:n], delivered[warmup:], strict=True)]
    parsed_ms = [(d - p) * 1000 for p, d in zip(parsed[warmup:], delivered[warmup:], strict=True)]
    return {
        "presses": presses,
        "warmup": warmup,
        "key_frame_to_delivered_ms": _percentiles(frame_ms),
        "key_parsed_to_delivered_ms": _percentiles(parsed_ms),
    }


def _percentiles(values: list[float]) -> dict[str, float]:
    ordered = sorted(values)

    def pct(p: float) -> float:
        return ordered[min(len(ordered) - 1, round(p / 100 * (len(ordered) - 1)))]

    return {"p50": pct(50), "p99": pct(99), "max": ordered[-1], "mean": statistics.fmean(ordered)}


# -- report ----------------------------------------------------------------------------------
def report(results: dict[str, Any]) -> str:
    s, i, k = results["startup"], results["idle"], results["keys"]
    rss = max(i["rss_after_start_mb"], i["rss_after_idle_mb"])
    rows = [
        (
            f"start-up to ready (median of {len(s['startup_s'])})",
            f"{s['startup_median_s']:.2f} s",
            "  ".join(f"{t:.2f}" for t in s["startup_s"]),
        ),
        (
            f"idle CPU over {i['idle_window_s']:.0f} s, no browser",
            f"{i['idle_cpu_pct']:.2f} % of a core",
            f"aim < {AIMS['idle_cpu_pct']:.0f} %: {'met' if i['idle_cpu_pct'] < AIMS['idle_cpu_pct'] else 'MISSED'}",
        ),
        ("RSS after start", f"{i['rss_after_start_mb']:.1f} MiB", ""),
        (
            "RSS after idle",
            f"{i['rss_after_idle_mb']:.1f} MiB",
            f"aim < {AIMS['rss_mb']:.0f} MB: {'met' if rss < AIMS['rss_mb'] else 'MISSED'}",
        ),
        ("key frame → /keydown delivered p50", f"{k['key_frame_to_delivered_ms']['p50']:.3f} ms", ""),
        (
            "key frame → /keydown delivered p99",
            f"{k['key_frame_to_delivered_ms']['p99']:.3f} ms",
            f"aim < {AIMS['key_p99_ms']:.0f} ms: "
            f"{'met' if k['key_frame_to_delivered_ms']['p99'] < AIMS['key_p99_ms'] else 'MISSED'}",
        ),
        ("key_down() → /keydown delivered p50", f"{k['key_parsed_to_delivered_ms']['p50']:.3f} ms", ""),
        ("key_down() → /keydown delivered p99", f"{k['key_parsed_to_delivered_ms']['p99']:.3f} ms", ""),
    ]
    width = max(len(r[0]) for r in rows)
    m = results["machine"]
    lines = [f"machine: {m['nproc']} CPU(s), {m['cpu_model']}; Python {m['python']}; {m['platform']}", ""]
    lines += [f"{name:<{width}}  {value:>18}  {note}".rstrip() for name, value, note in rows]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--starts", type=int, default=5)
    parser.add_argument("--idle-s", type=float, default=20.0)
    parser.add_argument("--presses", type=int, default=1000)
    parser.add_argument("--warmup", type=int, default=50)
    args = parser.parse_args(argv)

    results: dict[str, Any] = {
        "when": datetime.now(UTC).isoformat(timespec="seconds"),
        "machine": machine_info(),
    }
    results["startup"] = bench_startup(args.starts)
    results["idle"] = bench_idle(args.idle_s)
    results["keys"] = bench_keys(args.presses, args.warmup)
    print(report(results))
    RESULTS.mkdir(parents=True, exist_ok=True)
    out = RESULTS / f"startup_idle_keys_{datetime.now().strftime('%Y%m%d_%H%M%S')}.json"
    out.write_text(json.dumps(results, indent=2))
    print(f"\nJSON: {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
