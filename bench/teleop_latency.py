"""Bench: key-to-motion latency of the drone teleop as the page's HUD measures it, in a real
headless Chromium, for the keyboard manager's ``lab`` (20 Hz, 1 m per press) and ``hold`` modes;
and the same interval in process on a ManualClock, to split physics/control time from transport
and rendering time.

    .venv/bin/python bench/teleop_latency.py [--presses 100] [--modes lab hold] [--trials 100]

What is measured, exactly (docs/teleop.md has the why):

* browser, per mode: ``python -m server --launch fly keyboard_mode:=MODE`` in a subprocess, one
  1000x650 Chromium page (SwiftShader WebGL, viser.md §4's flags). After the page has drawn
  steadily for 2 s and the drone hovers, ``--presses`` presses alternate ArrowRight/ArrowLeft (so
  the drone stays near x = 0): in lab mode a press is keydown+keyup, in hold mode the key is held
  0.3 s. For each press the bench waits (at most 3 s from the keydown) for a new entry in
  ``window.__teleopHud.latencies``: static/hud.js's key→motion interval, from the keydown event's
  timeStamp to the receipt, in the page, of the first /uav/sensors/gps pose that shows the drone
  tilted 0.3° more towards the key (or moved 2 cm that way). A press without one counts as timed
  out. Between presses the drone settles (the HUD's pose within 2 cm for 3 × 200 ms and within
  10 cm of the setpoint, at most 8 s; presses after an unsettled wait are counted).
  Also: ``window.__teleopHud.poseRate`` (poses received in the last second) sampled after each
  press and averaged; CPU (utime+stime from /proc/<pid>/stat) of the server process and, for
  information, of every Chromium process, over the press loop, as % of one core.
* in process, per mode: the app's Lab (``Settings(launch='fly', viewer=False)``) on a ManualClock,
  stepped by hand in 0.5 ms steps after a ``lab.keyboard.key_down``; the interval (simulated time)
  to the first /uav/sensors/gps message meeting the HUD's criterion, for ``--trials`` presses with
  the same press pattern, each at a random phase of the 20 Hz tick (seeded). No network, no
  browser, no rendering, no scheduling: the physics and control chain alone.

Results: a table with the machine's details; JSON in bench/results/ (git-ignored).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import time
from datetime import datetime
from pathlib import Path
from typing import Any

import httpx
import numpy as np

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))  # the app's packages live at the root

from machine import machine_info
from startup_idle_keys import ServerProcess, cpu_seconds, free_port

RESULTS = REPO / "bench" / "results"
import contextlib

from machine import CHROMIUM, CHROMIUM_ARGS

VIEWPORT = {"width": 1000, "height": 650}
KEYS = ("ArrowRight", "ArrowLeft")
HOLD_S = {"lab": 0.0, "hold": 0.3}
ANSWER_TIMEOUT_S = 3.0  # the HUD itself gives up on a press after 3 s
SETTLE_TIMEOUT_MS = 8_000
PAGE_TIMEOUT_MS = 60_000
STEP_S = 0.0005
TICK_S = 0.05  # lab mode's 20 Hz timer
WARMUP_S = 8.0  # the drone takes off to (0, 0, 3) and hovers
SETTLE_S = 2.5  # simulated settling between in-process presses
MOTION_M = 0.02  # the HUD's criteria (static/hud.js)
TILT_RAD = math.radians(0.3)

FRAME_MONITOR_JS = """(() => {
  const m = { count: 0, last: performance.now(), lastStall: performance.now() };
  window.__frames = m;
  const tick = (now) => { if (now - m.last > 400) m.lastStall = now; m.last = now; m.count++;
    requestAnimationFrame(tick); };
  requestAnimationFrame(tick);
})();"""
# For the split of each HUD latency into legs: every keydown's timeStamp (this listener is added
# before keys.js's, which stops arrow keys) and every /uav/sensors/gps pose the page receives,
# with its receipt time and its header stamp (the server's clock when the dynamics published it).
LEGS_JS = """(() => {
  const log = { keys: [], gps: [] };
  window.__bench = log;
  addEventListener('keydown', (e) => { if (!e.repeat) log.keys.push(e.timeStamp); }, true);
  const Native = window.WebSocket;
  window.WebSocket = class extends Native {
    constructor(url, protocols) {
      super(url, protocols);
      if (String(url).includes('/ws/topics/uav/sensors/gps')) this.addEventListener('message', (ev) => {
        const s = JSON.parse(ev.data).msg.header.stamp;
        log.gps.push([performance.now(), s.sec + s.nanosec * 1e-9]);
        if (log.gps.length > 3000) log.gps.splice(0, 1000);
      });
    }
  };
})();"""
LEG_OF_PRESS_JS = """(latency) => {
  const b = window.__bench, t0 = b.keys[b.keys.length - 1], recv = t0 + latency;
  let best = null;
  for (const g of b.gps) if (best === null || Math.abs(g[0] - recv) < Math.abs(best[0] - recv)) best = g;
  return { origin: performance.timeOrigin, t0, recv: best && best[0], stamp: best && best[1] };
}"""
ECHO_WINDOW_S = 5.0
MATCH_MS = 0.5  # the pose the HUD answered with was received within this of the HUD's own clock reading
SETTLED_JS = "() => window.__frames.count > 20 && performance.now() - window.__frames.lastStall > 2000"
# The drone has settled when the HUD's pose has stayed within 2 cm for 3 windows of 200 ms in a
# row and sits within 10 cm of the HUD's setpoint: one still window is not enough, since an
# overshoot's turning point is still for a moment, and the return swing then runs in the next
# press's direction (alternating keys) and would answer it before the key could have.
DRONE_SETTLED_JS = """async (timeoutMs) => {
  const hud = window.__teleopHud, t0 = performance.now();
  let prev = hud.pose, still = 0;
  while (performance.now() - t0 < timeoutMs) {
    await new Promise((r) => setTimeout(r, 200));
    const cur = hud.pose, sp = hud.setpoint;
    const moved = prev && cur ? Math.hypot(cur[0] - prev[0], cur[1] - prev[1], cur[2] - prev[2]) : 1;
    const near = !sp || (cur && Math.hypot(cur[0] - sp[0], cur[1] - sp[1], cur[2] - sp[2]) < 0.1);
    still = moved < 0.02 && near ? still + 1 : 0;
    if (still >= 3) return true;
    prev = cur;
  }
  return false;
}"""


# -- processes ---------------------------------------------------------------------------------
class FlyServer(ServerProcess):
    """``python -m server --launch fly keyboard_mode:=MODE`` (startup_idle_keys' rocket server, re-launched)."""

    def __init__(self, mode: str) -> None:  # replaces the parent's command; wait_ready and stop are its own
        self.port = free_port()
        self.url = f"http://127.0.0.1:{self.port}"
        self.spawned_at = time.perf_counter()
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "server", "--launch", "fly", f"keyboard_mode:={mode}", "--host", "127.0.0.1",
             "--port", str(self.port), "--log-level", "warning"],
            cwd=REPO, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
        )  # fmt: skip


def descendants(root: int) -> list[int]:
    children: dict[int, list[int]] = {}
    for entry in Path("/proc").iterdir():
        try:
            ppid = int((entry / "stat").read_text().rsplit(")", 1)[1].split()[1])
            children.setdefault(ppid, []).append(int(entry.name))
        except (OSError, ValueError, IndexError):
            continue
    found, stack = [], [root]
    while stack:
        for pid in children.get(stack.pop(), []):
            found.append(pid)
            stack.append(pid)
    return found


def chromium_cpu_s() -> dict[int, float]:
    """CPU seconds of each Chromium process this bench started (Playwright's driver is its child)."""
    out = {}
    for pid in descendants(os.getpid()):
        try:
            if b"chromium" in Path(f"/proc/{pid}/cmdline").read_bytes():
                out[pid] = cpu_seconds(pid)
        except OSError:
            continue
    return out


def percentiles(values: list[float]) -> dict[str, float | None]:
    if not values:
        return {"p50": None, "p95": None, "min": None, "max": None, "n": 0}
    a = np.asarray(values)
    return {"p50": float(np.percentile(a, 50)), "p95": float(np.percentile(a, 95)), "min": float(a.min()),
            "max": float(a.max()), "n": len(values)}  # fmt: skip


# -- in the browser ----------------------------------------------------------------------------
def bench_browser(mode: str, presses: int) -> dict[str, Any]:
    from playwright.sync_api import Error as PlaywrightError
    from playwright.sync_api import sync_playwright

    server = FlyServer(mode)
    try:
        server.wait_ready()
        with sync_playwright() as playwright:
            browser = playwright.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)
            try:
                context = browser.new_context(viewport=VIEWPORT)
                context.add_init_script(FRAME_MONITOR_JS)
                context.add_init_script(LEGS_JS)
                page = context.new_page()
                page.set_default_timeout(PAGE_TIMEOUT_MS)
                page.goto(server.url + "/")
                page.wait_for_function(
                    "() => window.__teleopKeys !== undefined && window.__teleopKeys.connected"
                )
                page.wait_for_function("() => window.__teleopHud.pose !== null")
                try:
                    page.wait_for_function(SETTLED_JS, polling=100, timeout=30_000)
                except PlaywrightError:
                    print(f"  [{mode}] the page never drew steadily for 2 s; measuring anyway", flush=True)
                for button in page.locator(".mantine-Notification-closeButton").all():
                    with contextlib.suppress(PlaywrightError):
                        button.click(timeout=2_000)
                page.evaluate(DRONE_SETTLED_JS, SETTLE_TIMEOUT_MS)
                result = _press_loop(page, server, mode, presses, PlaywrightError)
                result["echo_without_page_ms"] = percentiles(echo_leg_ms(server))  # the page still open
                return result
            finally:
                browser.close()
    finally:
        server.stop()


def _press_loop(
    page: Any, server: FlyServer, mode: str, presses: int, error: type[Exception]
) -> dict[str, Any]:
    latencies: list[float] = []
    legs: dict[str, list[float]] = {"input": [], "server": [], "output": []}
    timed_out = unsettled = 0
    rates: list[float] = []
    cpu0, chrome0, wall0 = cpu_seconds(server.proc.pid), chromium_cpu_s(), time.monotonic()
    for i in range(presses):
        key = KEYS[i % 2]
        before = page.evaluate("window.__teleopHud.latencies.length")
        pressed = time.monotonic()
        page.keyboard.down(key)
        if HOLD_S[mode]:
            time.sleep(HOLD_S[mode])  # the hold itself
        page.keyboard.up(key)
        remaining_ms = max(100, round((ANSWER_TIMEOUT_S - (time.monotonic() - pressed)) * 1000))
        try:
            page.wait_for_function(
                "(n) => window.__teleopHud.latencies.length > n", arg=before, timeout=remaining_ms
            )
        except error:
            timed_out += 1
        else:
            latency = page.evaluate("window.__teleopHud.latencies[window.__teleopHud.latencies.length - 1]")
            latencies.append(latency)
            _split(page, server, latency, legs)
        if not page.evaluate(DRONE_SETTLED_JS, SETTLE_TIMEOUT_MS):
            unsettled += 1
        rates.append(page.evaluate("window.__teleopHud.poseRate"))
        if (i + 1) % 20 == 0:
            print(f"  [{mode}] {i + 1}/{presses} presses, median so far {statistics.median(latencies or [0]):.0f} ms",
                  flush=True)  # fmt: skip
    wall = time.monotonic() - wall0
    cpu1, chrome1 = cpu_seconds(server.proc.pid), chromium_cpu_s()
    chrome_s = sum(chrome1[p] - chrome0[p] for p in chrome1 if p in chrome0)
    return {
        "presses": presses,
        "hold_s": HOLD_S[mode],
        "latency_ms": percentiles(latencies),
        "legs_ms": {name: percentiles(values) for name, values in legs.items()},
        "latencies_ms": latencies,
        "timed_out": timed_out,
        "not_settled_before_next": unsettled,
        "pose_rate_hz_mean": statistics.fmean(rates) if rates else None,
        "window_s": wall,
        "server_cpu_pct": 100 * (cpu1 - cpu0) / wall,
        "chromium_cpu_pct": 100 * chrome_s / wall,
    }


def _split(page: Any, server: FlyServer, latency_ms: float, legs: dict[str, list[float]]) -> None:
    """One press's latency in three legs on the host's wall clock (the page's timeOrigin + now,
    and the server's stamps): keydown → /keydown published (browser input, the key channel's
    WebSocket, parsing); → the answering pose published (physics and control, in real time);
    → that pose received in the page (the echo WebSocket and the page's busy main thread)."""
    leg = page.evaluate(LEG_OF_PRESS_JS, latency_ms)
    if leg["recv"] is None or abs(leg["recv"] - (leg["t0"] + latency_ms)) > MATCH_MS:
        return
    stamp = httpx.get(f"{server.url}/api/topics/keydown", timeout=5).json()["latest"]["header"]["stamp"]
    key_s = stamp["sec"] + stamp["nanosec"] * 1e-9
    pressed_s, received_s = (leg["origin"] + leg["t0"]) / 1000, (leg["origin"] + leg["recv"]) / 1000
    legs["input"].append((key_s - pressed_s) * 1000)
    legs["server"].append((leg["stamp"] - key_s) * 1000)
    legs["output"].append((received_s - leg["stamp"]) * 1000)


def echo_leg_ms(server: FlyServer, window_s: float = ECHO_WINDOW_S) -> list[float]:
    """The output leg without a page: a Python client of the same /uav/sensors/gps echo WebSocket,
    from each pose's stamp to its receipt (the server's send loop and loopback TCP)."""
    from websockets.sync.client import connect

    out = []
    with connect(f"ws://127.0.0.1:{server.port}/ws/topics/uav/sensors/gps?queue_length=10") as ws:
        end = time.monotonic() + window_s
        while time.monotonic() < end:
            stamp = json.loads(ws.recv(timeout=PAGE_TIMEOUT_MS / 1000))["msg"]["header"]["stamp"]
            out.append((time.time() - (stamp["sec"] + stamp["nanosec"] * 1e-9)) * 1000)
    return out


# -- in process, on a ManualClock --------------------------------------------------------------
def tilt_toward_x(q: Any) -> float:
    """static/hud.js's tiltToward(q, 0): the pitch that moves the drone towards +x."""
    return math.asin(max(-1.0, min(1.0, 2 * (q.w * q.y - q.z * q.x))))


def bench_in_process(mode: str, trials: int, seed: int = 1) -> dict[str, Any]:
    from server.bus import ManualClock
    from server.lab import Lab
    from server.msgs import Key
    from server.settings import Settings

    rng = np.random.default_rng(seed)
    lab = Lab(Settings(launch="fly", viewer=False, launch_args={"keyboard_mode": mode}), ManualClock(0.0))
    lab.start_nodes()
    executor, gps = lab.executor, lab.bus.topics["/uav/sensors/gps"]
    t = WARMUP_S
    executor.spin_until(t)
    latencies, timed_out = [], 0
    codes = (Key.KEY_RIGHT, Key.KEY_LEFT)
    for i in range(trials):
        t += rng.uniform(0.0, TICK_S)  # a random phase of the 20 Hz tick and of the control loops
        executor.spin_until(t)
        code, sign = codes[i % 2], (1.0, -1.0)[i % 2]
        start = gps.latest
        x0, tilt0, t0 = start.pose.position.x, tilt_toward_x(start.pose.orientation), t
        lab.keyboard.key_down(code, 0, "bench")
        if not HOLD_S[mode]:
            lab.keyboard.key_up(code, 0, "bench")
        answered = None
        last = start
        while t - t0 < ANSWER_TIMEOUT_S:
            t += STEP_S
            executor.spin_until(t)
            msg = gps.latest
            if msg is last:
                continue
            last = msg
            moved = (msg.pose.position.x - x0) * sign
            tilted = (tilt_toward_x(msg.pose.orientation) - tilt0) * sign
            if moved >= MOTION_M or tilted >= TILT_RAD:
                answered = t - t0
                break
        if answered is None:
            timed_out += 1
        else:
            latencies.append(answered * 1000)
        if HOLD_S[mode]:
            t = max(t, t0 + HOLD_S[mode])
            executor.spin_until(t)
            lab.keyboard.key_up(code, 0, "bench")
        t += SETTLE_S
        executor.spin_until(t)
    return {"trials": trials, "latency_ms": percentiles(latencies), "timed_out": timed_out,
            "step_ms": STEP_S * 1000}  # fmt: skip


# -- report ------------------------------------------------------------------------------------
def fmt(value: float | None, spec: str = ".0f") -> str:
    return "–" if value is None else format(value, spec)


def report(results: dict[str, Any]) -> str:
    m = results["machine"]
    lines = [f"machine: {m['nproc']} CPU(s), {m['cpu_model']}; Python {m['python']}; {m['platform']}", ""]
    header = (f"{'mode':<5} {'presses':>7} {'timed out':>9} {'HUD p50':>8} {'HUD p95':>8} {'sim p50':>8} "
              f"{'sim p95':>8} {'p50 − sim':>9} {'poses/s':>8} {'server CPU':>10} {'Chromium CPU':>12}")  # fmt: skip
    lines += [header, "-" * len(header)]
    for mode, r in results["modes"].items():
        b, s = r["browser"], r["in_process"]
        rest = None if b["latency_ms"]["p50"] is None else b["latency_ms"]["p50"] - s["latency_ms"]["p50"]
        lines.append(
            f"{mode:<5} {b['presses']:>7} {b['timed_out']:>9} {fmt(b['latency_ms']['p50']):>5} ms "
            f"{fmt(b['latency_ms']['p95']):>5} ms {fmt(s['latency_ms']['p50']):>5} ms {fmt(s['latency_ms']['p95']):>5} ms "
            f"{fmt(rest):>6} ms {fmt(b['pose_rate_hz_mean']):>8} {fmt(b['server_cpu_pct'], '.0f'):>8} % "
            f"{fmt(b['chromium_cpu_pct'], '.0f'):>10} %"
        )  # fmt: skip
    lines += [
        "",
        (
            "legs of the HUD latency (p50 / p95, ms; host wall clock): keydown → /keydown published → "
            "answering pose published → received in the page"
        ),
    ]
    for mode, r in results["modes"].items():
        legs = r["browser"]["legs_ms"]
        lines.append(f"{mode:<5} " + "   ".join(
            f"{name} {fmt(legs[name]['p50'])} / {fmt(legs[name]['p95'])} (n {legs[name]['n']})"
            for name in ("input", "server", "output")))  # fmt: skip
    for mode, r in results["modes"].items():
        lines.append(f"{mode:<5} HUD latencies below the in-process minimum (answered by motion already under way): "
                     f"{len(r['below_in_process_min'])}; waits that ended unsettled: "
                     f"{r['browser']['not_settled_before_next']}")  # fmt: skip
    for mode, r in results["modes"].items():
        echo = r["browser"]["echo_without_page_ms"]
        lines.append(f"{mode:<5} output leg to a Python client instead of the page: {fmt(echo['p50'], '.1f')} / "
                     f"{fmt(echo['p95'], '.1f')} (n {echo['n']})")  # fmt: skip
    lines += ["", "HUD: static/hud.js's key→motion, in the page; sim: the same criterion in process on a ManualClock",
              "(physics and control only); p50 − sim: transport, scheduling and the page's main thread.",
              "CPU: % of one core over the press loop."]  # fmt: skip
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--presses", type=int, default=100, help="browser presses per mode")
    parser.add_argument("--trials", type=int, default=100, help="in-process presses per mode")
    parser.add_argument("--modes", nargs="+", default=["lab", "hold"], choices=["lab", "hold", "adopt"])
    args = parser.parse_args(argv)
    if not Path(CHROMIUM).is_file():
        print(f"no Chromium at {CHROMIUM}: apt-get install chromium", file=sys.stderr)
        return 2
    HOLD_S.setdefault("adopt", 0.0)

    results: dict[str, Any] = {"when": datetime.now().astimezone().isoformat(timespec="seconds"),
                               "machine": machine_info(), "load_avg_start": os.getloadavg(), "modes": {}}  # fmt: skip
    for mode in args.modes:
        print(f"{mode}: in process ({args.trials} presses on a ManualClock) ...", flush=True)
        in_process = bench_in_process(mode, args.trials)
        print(f"{mode}: in Chromium ({args.presses} presses) ...", flush=True)
        browser = bench_browser(mode, args.presses)
        floor = in_process["latency_ms"]["min"]
        below = [v for v in browser["latencies_ms"] if floor is not None and v < floor]
        results["modes"][mode] = {"browser": browser, "in_process": in_process, "below_in_process_min": below}
    results["load_avg_end"] = os.getloadavg()
    print()
    print(report(results))
    print(
        f"\nload average at start {results['load_avg_start'][0]:.2f}, at end {results['load_avg_end'][0]:.2f}"
    )
    RESULTS.mkdir(parents=True, exist_ok=True)
    out = RESULTS / f"teleop_latency_{datetime.now().strftime('%Y%m%d_%H%M%S')}.json"
    out.write_text(json.dumps(results, indent=2))
    print(f"JSON: {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
