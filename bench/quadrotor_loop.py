"""The quadrotor lab's loop: how fast it runs stepped by hand, what it costs in real time, how late its timers fire.

Run from the repository root:  .venv/bin/python bench/quadrotor_loop.py [--runs 5] [--seconds 20]

1. in-process, ManualClock: the full fly launch stepped as fast as it goes; sim seconds per wall
   second, median of --runs runs of --sim-seconds each;
2. real time: ``python -m server --launch fly`` as a subprocess; its CPU share (utime + stime from
   /proc/<pid>/stat) over --seconds with no browser, then with one headless Chromium on its page
   (Playwright, /usr/bin/chromium); Chromium's own share is given for information;
3. timer lateness: the fly launch on the system clock in an asyncio loop (the app's executor, no
   HTTP) for --seconds; p50/p99/max of each timer's ``lateness_s`` for the dynamics node and the
   controllers, with the viser display off and on (no browser).
Results go to bench/results/quadrotor_loop.json (git-ignored).
"""

from __future__ import annotations

import argparse
import asyncio
import json
import os
import statistics
import subprocess
import sys
import time
import urllib.request
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np

REPO_ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO_ROOT))

from live_server import free_port
from machine import (
    CHROMIUM,
    machine_info,
)
from machine import CHROMIUM_ARGS as CHROMIUM_FLAGS

from node_runtime.bus import ManualClock, SystemClock
from server.host.settings import LabSettings, Settings
from server.world.lab import Lab

CLK_TCK = os.sysconf("SC_CLK_TCK")
SETTLE_S = 3.0  # after start-up (or page load) before measuring
TIMED_NODES = (
    "flightgoggles_uav_dynamics",
    "position_controller_node",
    "velocity_controller_node",
    "angle_controller_node",
    "GUI_Controller_Node",
)


# -- machine -------------------------------------------------------------------------------------
# -- 1. in-process, as fast as it goes -----------------------------------------------------------
def manual_clock_run(sim_seconds: float) -> tuple[float, int]:
    """One fly launch stepped to ``sim_seconds``; returns (sim s per wall s, callbacks run)."""
    lab = Lab(Settings(lab=LabSettings(launch="fly", viewer=False)), ManualClock(0.0))
    lab.start_nodes()
    start = time.perf_counter()
    lab.executor.spin_until(sim_seconds)
    wall_s = time.perf_counter() - start
    lab.launcher.shutdown()
    return sim_seconds / wall_s, lab.executor.callbacks_run


def bench_manual_clock(runs: int, sim_seconds: float) -> dict[str, Any]:
    manual_clock_run(2.0)  # warm-up: imports, caches
    results = [manual_clock_run(sim_seconds) for _ in range(runs)]
    speeds = [s for s, _ in results]
    return {
        "median_sim_s_per_wall_s": statistics.median(speeds),
        "runs_sim_s_per_wall_s": speeds,
        "sim_seconds_per_run": sim_seconds,
        "callbacks_per_sim_s": results[0][1] / sim_seconds,
    }


# -- 2. the real-time server's CPU -----------------------------------------------------------------
def cpu_ticks(pid: int) -> int:
    """utime + stime of one process, in clock ticks (fields 14 and 15 of /proc/<pid>/stat)."""
    text = Path(f"/proc/{pid}/stat").read_text()
    fields = text[text.rindex(")") + 2 :].split()  # the name may hold spaces and parentheses
    return int(fields[11]) + int(fields[12])


def children_map() -> dict[int, list[int]]:
    tree: dict[int, list[int]] = {}
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            text = (entry / "stat").read_text()
        except OSError:
            continue
        ppid = int(text[text.rindex(")") + 2 :].split()[1])
        tree.setdefault(ppid, []).append(int(entry.name))
    return tree


def descendants(pid: int, exclude: set[int]) -> list[int]:
    tree, found, stack = children_map(), [], [pid]
    while stack:
        for child in tree.get(stack.pop(), []):
            if child not in exclude:
                found.append(child)
                stack.append(child)
    return found


def process_name(pid: int) -> str:
    try:
        return Path(f"/proc/{pid}/comm").read_text().strip()
    except OSError:
        return ""


def chromium_pids(server_pid: int) -> list[int]:
    """Chromium's processes: this script's descendants named like it (not the server, not the driver)."""
    return [p for p in descendants(os.getpid(), {server_pid}) if "chrom" in process_name(p).lower()]


def measure_cpu(pids_now: Any, seconds: float) -> tuple[float, int]:
    """CPU share (1.0 = one core) of the processes ``pids_now()`` names, over ``seconds`` of wall time."""

    def total() -> tuple[int, set[int]]:
        ticks, seen = 0, set()
        for pid in pids_now():
            try:
                ticks += cpu_ticks(pid)
                seen.add(pid)
            except OSError:
                pass
        return ticks, seen

    t0, (ticks0, pids0) = time.monotonic(), total()
    time.sleep(seconds)
    t1, (ticks1, pids1) = time.monotonic(), total()
    # Processes that came or went in between are counted from zero or dropped: Chromium's
    # helpers live for the whole page, so only the server's figure needs to be exact.
    return (ticks1 - ticks0) / CLK_TCK / (t1 - t0), len(pids0 | pids1)


def wait_for_health(port: int, timeout_s: float = 30.0) -> None:
    end = time.monotonic() + timeout_s
    while time.monotonic() < end:
        try:
            with urllib.request.urlopen(f"http://127.0.0.1:{port}/api/health", timeout=1.0) as r:
                if r.status == 200:
                    return
        except OSError:
            time.sleep(0.1)
    raise RuntimeError(f"the server on port {port} did not answer /api/health within {timeout_s} s")


@contextmanager
def server_process(port: int) -> Iterator[subprocess.Popen[bytes]]:
    cmd = [sys.executable, "-m", "server", "--launch", "fly", "--port", str(port), "--log-level", "warning"]
    proc = subprocess.Popen(cmd, cwd=REPO_ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        wait_for_health(port)
        yield proc
    finally:
        proc.terminate()
        try:
            proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()


def bench_real_time(seconds: float) -> dict[str, Any]:
    port = free_port()
    result: dict[str, Any] = {"seconds": seconds}
    with server_process(port) as proc:
        time.sleep(SETTLE_S)
        share, _ = measure_cpu(lambda: [proc.pid], seconds)
        result["server_cpu_no_browser"] = share
        try:
            from playwright.sync_api import sync_playwright
        except ImportError:
            result["browser"] = "playwright not installed"
            return result
        if not Path(CHROMIUM).exists():
            result["browser"] = f"{CHROMIUM} not found"
            return result
        with sync_playwright() as pw:
            browser = pw.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_FLAGS)
            page = browser.new_page(viewport={"width": 1280, "height": 800})
            page.goto(f"http://127.0.0.1:{port}/", wait_until="load")
            page.wait_for_selector("canvas", timeout=30_000)
            time.sleep(SETTLE_S)
            server0 = cpu_ticks(proc.pid)
            t0 = time.monotonic()
            chromium_share, n = measure_cpu(lambda: chromium_pids(proc.pid), seconds)
            server_share = (cpu_ticks(proc.pid) - server0) / CLK_TCK / (time.monotonic() - t0)
            result["server_cpu_with_browser"] = server_share
            result["chromium_cpu"] = chromium_share
            result["chromium_processes"] = n
            browser.close()
    return result


# -- 3. timer lateness on the system clock ---------------------------------------------------------
async def run_lab_real_time(seconds: float, viewer: bool) -> dict[str, dict[str, float]]:
    lab = Lab(Settings(lab=LabSettings(launch="fly", viewer=viewer)), SystemClock())
    await lab.start()
    try:
        await asyncio.sleep(SETTLE_S)  # start-up is not the steady loop
        timers = [(name, i, t) for name in TIMED_NODES for i, t in enumerate(lab.bus.get_node(name).timers)]
        calls0 = {id(t): t.call_count for _, _, t in timers}
        for _, _, timer in timers:
            timer.lateness_s.clear()
        await asyncio.sleep(seconds)
        out: dict[str, dict[str, float]] = {}
        for name, i, timer in timers:
            late_ms = np.array(timer.lateness_s) * 1e3
            if late_ms.size == 0:
                continue
            key = name if len(lab.bus.get_node(name).timers) == 1 else f"{name}[{i}]"
            out[key] = {
                "period_ms": timer.period_s * 1e3,
                "calls": timer.call_count - calls0[id(timer)],
                "expected_calls": seconds / timer.period_s,
                "samples": int(late_ms.size),
                "p50_ms": float(np.percentile(late_ms, 50)),
                "p99_ms": float(np.percentile(late_ms, 99)),
                "max_ms": float(late_ms.max()),
            }
        return out
    finally:
        await lab.stop()


def bench_lateness(seconds: float) -> dict[str, Any]:
    return {
        "seconds": seconds,
        "viewer_off": asyncio.run(run_lab_real_time(seconds, viewer=False)),
        "viewer_on_no_browser": asyncio.run(run_lab_real_time(seconds, viewer=True)),
    }


# -- report --------------------------------------------------------------------------------------
def print_report(info: dict[str, Any], results: dict[str, Any]) -> None:
    print("machine:", ", ".join(f"{k}={v}" for k, v in info.items()))
    mc = results["manual_clock"]
    print(
        f"\n1. fly launch on a ManualClock: {mc['median_sim_s_per_wall_s']:.1f} sim s per wall s "
        f"(median of {len(mc['runs_sim_s_per_wall_s'])} x {mc['sim_seconds_per_run']:g} s; "
        f"{mc['callbacks_per_sim_s']:.0f} callbacks per sim s)"
    )
    rt = results["real_time"]
    print(f"\n2. python -m server --launch fly, CPU share of one core over {rt['seconds']:g} s:")
    print(f"   {'server, no browser':34s} {rt['server_cpu_no_browser'] * 100:6.1f} %")
    if "server_cpu_with_browser" in rt:
        print(f"   {'server, one headless Chromium':34s} {rt['server_cpu_with_browser'] * 100:6.1f} %")
        print(
            f"   {'Chromium (information)':34s} {rt['chromium_cpu'] * 100:6.1f} %  "
            f"({rt['chromium_processes']} processes)"
        )
    else:
        print(f"   browser: {rt.get('browser')}")
    lt = results["lateness"]
    print(f"\n3. timer lateness on the system clock over {lt['seconds']:g} s (ms):")
    print(f"   {'timer':34s} {'period':>7s} {'calls/expected':>15s} {'p50':>7s} {'p99':>7s} {'max':>7s}")
    for variant in ("viewer_off", "viewer_on_no_browser"):
        print(f"   -- {variant}")
        for name, s in lt[variant].items():
            calls = f"{s['calls']}/{s['expected_calls']:.0f}"
            print(
                f"   {name:34s} {s['period_ms']:7.1f} {calls:>15s} {s['p50_ms']:7.3f} "
                f"{s['p99_ms']:7.3f} {s['max_ms']:7.3f}"
            )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--sim-seconds", type=float, default=20.0, help="sim time per ManualClock run")
    parser.add_argument("--seconds", type=float, default=20.0, help="wall time per real-time measurement")
    parser.add_argument("--json", type=Path, default=REPO_ROOT / "bench" / "results" / "quadrotor_loop.json")
    args = parser.parse_args()
    if args.runs < 5:
        parser.error("--runs must be >= 5 (figures are medians)")

    info = machine_info()
    results: dict[str, Any] = {
        "manual_clock": bench_manual_clock(args.runs, args.sim_seconds),
        "real_time": bench_real_time(args.seconds),
        "lateness": bench_lateness(args.seconds),
    }
    info["load_average_at_end"] = os.getloadavg()
    print_report(info, results)
    args.json.parent.mkdir(parents=True, exist_ok=True)
    args.json.write_text(json.dumps({"machine": info, "results": results}, indent=2))
    print(f"\nwrote {args.json}")


if __name__ == "__main__":
    main()
