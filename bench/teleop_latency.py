"""Bench: how soon the page answers a key, in a real headless Chromium on software WebGL
(SwiftShader, as on a machine without GPU acceleration), at two common laptop window sizes:

* key → answer drawn: from the keydown event's timeStamp to the end of the frame that showed the
  page's predicted setpoint marker (web/src/lab/answer.ts), for each of its two drawing paths (``dom``:
  a disc over the canvas, the next 3D frame skipped; ``scene``: the 3D marker in the next 3D frame),
  and in how many animation frames;
* key → drone moving: web/src/lab/hud.ts's figure, to the first drone pose, received in the page, that
  shows the drone answering (tilted 0.3° more towards the key, or moved 2 cm);
* the page's frame rate and what a frame costs its main thread (web/src/lab/scene.ts), the pixel ratio
  web/src/lab/quality.ts chose, and the poses per second the page receives;
* beside them, the in-process floor of key → drone moving (bench/teleop_floor.py).

    .venv/bin/python bench/teleop_latency.py [--presses 60] [--viewports 1000x650 1366x768]
                                             [--modes hold lab] [--trials 100]

For each mode and viewport: ``python -m server --launch fly keyboard_mode:=MODE`` and one page;
after it draws steadily and the drone hovers, ``--presses`` presses alternate → and ← (the drone
stays near x = 0) and the marker's path, dom, dom, scene, scene, ... (so both paths see both keys
and the same machine load): in ``lab`` and ``adopt`` mode a press is a keydown and a keyup, in
``hold`` mode the key is held 0.3 s. Each press waits (at most 3 s) for both answers, then for the
drone to settle (the HUD's pose within 2 cm for 3 × 200 ms and within 10 cm of the setpoint, at
most 8 s). Each latency of the HUD is also split into legs on the host's wall clock: keydown →
/keydown published (input) → the answering pose published (server) → that pose in the page's pose
worker (network) → in the page's main thread (main thread). CPU (utime+stime) of the server and of
all Chromium processes over the press loop, as % of one core.

Results: a table with the machine's details; JSON in bench/results/ (git-ignored). The machine is
often shared: quote ratios between the two paths, or against the floor, from the same run.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import statistics
import subprocess
import sys
import time
from datetime import datetime
from pathlib import Path
from typing import Any

import httpx

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))  # the app's packages live at the root

from machine import CHROMIUM, CHROMIUM_ARGS, machine_info
from startup_idle_keys import ServerProcess, cpu_seconds, free_port
from teleop_floor import HOLD_S, bench_in_process, percentiles

RESULTS = REPO / "bench" / "results"
KEYS = ("ArrowRight", "ArrowLeft")
PATHS = ("dom", "scene")
ANSWER_TIMEOUT_MS = 3_000  # the HUD itself gives up on a press after 3 s
SETTLE_TIMEOUT_MS = 8_000
PAGE_TIMEOUT_MS = 60_000
STEADY_TIMEOUT_MS = 30_000
MATCH_MS = 0.5  # the pose the HUD answered with arrived within this of the HUD's own reading

FRAME_MONITOR_JS = """(() => {
  const m = { count: 0, last: performance.now(), lastStall: performance.now() };
  window.__frames = m;
  const tick = (now) => { if (now - m.last > 400) m.lastStall = now; m.last = now; m.count++;
    requestAnimationFrame(tick); };
  requestAnimationFrame(tick);
})();"""
STEADY_JS = "() => window.__frames.count > 20 && performance.now() - window.__frames.lastStall > 2000"
# Every keydown's timeStamp (this listener is added before keys.js's, which stops arrow keys), and
# every pose the page's main thread receives: when, its stamp, and when the pose worker had it.
LEGS_JS = """(() => {
  const log = { keys: [], poses: [] };
  window.__bench = log;
  addEventListener('keydown', (e) => { if (!e.repeat) log.keys.push(e.timeStamp); }, true);
  const hook = () => {
    if (!window.__teleop) { setTimeout(hook, 50); return; }
    window.__teleop.poses.listeners.push((samples, _sp, received) => {
      for (const s of samples) log.poses.push([received, s.stamp, s.arrived]);
      if (log.poses.length > 3000) log.poses.splice(0, 1000);
    });
  };
  hook();
})();"""
LEG_OF_PRESS_JS = """(latency) => {
  const b = window.__bench, t0 = b.keys[b.keys.length - 1], recv = t0 + latency;
  let best = null;
  for (const p of b.poses) if (best === null || Math.abs(p[0] - recv) < Math.abs(best[0] - recv)) best = p;
  return { origin: performance.timeOrigin, t0, recv: best && best[0], stamp: best && best[1], arrived: best && best[2] };
}"""
# Settled: the HUD's pose within 2 cm for 3 windows of 200 ms in a row and within 10 cm of the
# setpoint (one still window is not enough: an overshoot's turning point is still for a moment).
DRONE_SETTLED_JS = """async (timeoutMs) => {
  const hud = window.__teleop.hud, t0 = performance.now();
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
PAGE_STATE_JS = """() => ({ fps: window.__teleop.quality.fps, frameMs: window.__teleop.quality.frameMs,
  dpr: window.__teleop.quality.dpr, poseRate: window.__teleop.hud.poseRate })"""


class FlyServer(ServerProcess):
    """``python -m server --launch fly keyboard_mode:=MODE`` (startup_idle_keys' server, re-launched)."""

    def __init__(self, mode: str) -> None:  # replaces the parent's command; wait_ready and stop are its own
        self.port = free_port()
        self.url = f"http://127.0.0.1:{self.port}"
        self.spawned_at = time.perf_counter()
        self.proc = subprocess.Popen(
            [
                sys.executable,
                "-m",
                "server",
                "--launch",
                "fly",
                f"keyboard_mode:={mode}",
                "--host",
                "127.0.0.1",
                "--port",
                str(self.port),
                "--zenoh-listen",
                f"tcp/127.0.0.1:{free_port()}",
                "--log-level",
                "warning",
            ],
            cwd=REPO,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            text=True,
        )


def chromium_cpu_s() -> dict[int, float]:
    """CPU seconds of each Chromium process this bench started (Playwright's driver is its child)."""
    children: dict[int, list[int]] = {}
    for entry in Path("/proc").iterdir():
        with contextlib.suppress(OSError, ValueError, IndexError):
            ppid = int((entry / "stat").read_text().rsplit(")", 1)[1].split()[1])
            children.setdefault(ppid, []).append(int(entry.name))
    out, stack = {}, [os.getpid()]
    while stack:
        for pid in children.get(stack.pop(), []):
            stack.append(pid)
            with contextlib.suppress(OSError):
                if b"chromium" in Path(f"/proc/{pid}/cmdline").read_bytes():
                    out[pid] = cpu_seconds(pid)
    return out


# -- in the browser ----------------------------------------------------------------------------
def bench_browser(mode: str, viewport: tuple[int, int], presses: int) -> dict[str, Any]:
    from playwright.sync_api import Error as PlaywrightError
    from playwright.sync_api import sync_playwright

    server = FlyServer(mode)
    try:
        server.wait_ready()
        with sync_playwright() as playwright:
            browser = playwright.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)
            try:
                context = browser.new_context(viewport={"width": viewport[0], "height": viewport[1]})
                context.add_init_script(FRAME_MONITOR_JS)
                context.add_init_script(LEGS_JS)
                page = context.new_page()
                page.set_default_timeout(PAGE_TIMEOUT_MS)
                page.goto(server.url + "/")
                page.wait_for_function("() => window.__teleop && window.__teleop.scene.ready")
                page.wait_for_function(
                    "() => window.__teleop.hud.pose !== null && window.__teleop.predict.params !== null"
                )
                try:
                    page.wait_for_function(STEADY_JS, polling=100, timeout=STEADY_TIMEOUT_MS)
                except PlaywrightError:
                    print(
                        f"  [{mode} {viewport}] the page never drew steadily for 2 s; measuring anyway",
                        flush=True,
                    )
                for button in page.locator(".mantine-Notification-closeButton").all():
                    with contextlib.suppress(PlaywrightError):
                        button.click(timeout=2_000)
                page.evaluate(DRONE_SETTLED_JS, SETTLE_TIMEOUT_MS)
                return _press_loop(page, server, mode, presses, PlaywrightError)
            finally:
                browser.close()
    finally:
        server.stop()


def _press_loop(
    page: Any, server: FlyServer, mode: str, presses: int, error: type[Exception]
) -> dict[str, Any]:
    drawn: dict[str, list[float]] = {p: [] for p in PATHS}
    frames: dict[str, list[int]] = {p: [] for p in PATHS}
    moving: list[float] = []
    legs: dict[str, list[float]] = {"input": [], "server": [], "network": [], "main_thread": []}
    states: list[dict[str, Any]] = []
    no_answer = no_motion = unsettled = 0
    cpu0, chrome0, wall0 = cpu_seconds(server.proc.pid), chromium_cpu_s(), time.monotonic()
    for i in range(presses):
        key, path = KEYS[i % 2], PATHS[(i // 2) % 2]
        page.evaluate(f"window.__teleop.answer.setPath('{path}')")
        n_drawn, n_moving = page.evaluate(
            "[window.__teleop.answer.drawn.length, window.__teleop.hud.latencies.length]"
        )
        pressed = time.monotonic()
        page.keyboard.down(key)
        if HOLD_S[mode]:
            time.sleep(HOLD_S[mode])  # the hold itself
        page.keyboard.up(key)
        try:
            page.wait_for_function(
                f"() => window.__teleop.answer.drawn.length > {n_drawn}", timeout=_left_ms(pressed)
            )
            entry = page.evaluate(f"window.__teleop.answer.drawn[{n_drawn}]")
            drawn[entry["path"]].append(entry["latencyMs"])
            frames[entry["path"]].append(entry["frames"])
        except error:
            no_answer += 1
        try:
            page.wait_for_function(
                f"() => window.__teleop.hud.latencies.length > {n_moving}", timeout=_left_ms(pressed)
            )
            latency = page.evaluate(f"window.__teleop.hud.latencies[{n_moving}]")
            moving.append(latency)
            _split(page, server, latency, legs)
        except error:
            no_motion += 1
        if not page.evaluate(DRONE_SETTLED_JS, SETTLE_TIMEOUT_MS):
            unsettled += 1
        states.append(page.evaluate(PAGE_STATE_JS))
        if (i + 1) % 20 == 0:
            print(f"  [{mode}] {i + 1}/{presses} presses", flush=True)
    wall = time.monotonic() - wall0
    cpu1, chrome1 = cpu_seconds(server.proc.pid), chromium_cpu_s()
    chrome_s = sum(chrome1[p] - chrome0[p] for p in chrome1 if p in chrome0)
    known = lambda name: [s[name] for s in states if s[name] is not None]  # noqa: E731
    return {
        "presses": presses,
        "hold_s": HOLD_S[mode],
        "answer_drawn_ms": {p: percentiles(v) for p, v in drawn.items()},
        "answer_frames": {p: percentiles([float(f) for f in v]) for p, v in frames.items()},
        "drone_moving_ms": percentiles(moving),
        "legs_ms": {name: percentiles(values) for name, values in legs.items()},
        "raw": {"answer_drawn_ms": drawn, "drone_moving_ms": moving},
        "no_answer_drawn": no_answer,
        "no_drone_motion": no_motion,
        "not_settled_before_next": unsettled,
        "fps_mean": statistics.fmean(known("fps")) if known("fps") else None,
        "frame_ms_median": statistics.median(known("frameMs")) if known("frameMs") else None,
        "dpr_seen": sorted(set(known("dpr"))),
        "pose_rate_hz_mean": statistics.fmean(known("poseRate")) if known("poseRate") else None,
        "window_s": wall,
        "server_cpu_pct": 100 * (cpu1 - cpu0) / wall,
        "chromium_cpu_pct": 100 * chrome_s / wall,
    }


def _left_ms(pressed: float) -> int:
    """What is left of the answer's wait, since the press (time.monotonic())."""
    return max(100, round(ANSWER_TIMEOUT_MS - (time.monotonic() - pressed) * 1000))


def _split(page: Any, server: FlyServer, latency_ms: float, legs: dict[str, list[float]]) -> None:
    """One HUD latency in legs on the host's wall clock (the page's timeOrigin + now, the pose
    worker's arrival stamps and the server's): keydown → /keydown published → the answering pose
    published → that pose in the page's pose worker → in the page's main thread."""
    leg = page.evaluate(LEG_OF_PRESS_JS, latency_ms)
    if leg["recv"] is None or abs(leg["recv"] - (leg["t0"] + latency_ms)) > MATCH_MS:
        return
    stamp = httpx.get(f"{server.url}/api/topics/keydown", timeout=5).json()["latest"]["header"]["stamp"]
    key_s = stamp["sec"] + stamp["nanosec"] * 1e-9
    pressed_s, received_s = (leg["origin"] + leg["t0"]) / 1000, (leg["origin"] + leg["recv"]) / 1000
    legs["input"].append((key_s - pressed_s) * 1000)
    legs["server"].append((leg["stamp"] - key_s) * 1000)
    legs["network"].append(leg["arrived"] - leg["stamp"] * 1000)
    legs["main_thread"].append(received_s * 1000 - leg["arrived"])


# -- report ------------------------------------------------------------------------------------
def fmt(value: float | None, spec: str = ".0f") -> str:
    return "–" if value is None else format(value, spec)


def pair(p: dict[str, Any]) -> str:
    return f"{fmt(p['p50'])} / {fmt(p['p95'])}"


def report(results: dict[str, Any]) -> str:
    m = results["machine"]
    lines = [
        f"machine: {m['nproc']} CPU(s), {m['cpu_model']}; Python {m['python']}; {m['platform']}",
        "",
        "latencies in ms, p50 / p95",
    ]
    header = (
        f"{'mode':<5} {'window':>9} {'answer drawn: dom':>18} {'scene':>10} {'frames dom/scene p95':>21} "
        f"{'drone moving':>13} {'floor':>10} {'fps':>5} {'frame ms':>8} {'pixel ratio':>12} {'poses/s':>7} "
        f"{'server CPU':>10} {'Chromium CPU':>12}"
    )
    lines += [header, "-" * len(header)]
    for mode, per in results["modes"].items():
        floor = per["in_process"]["latency_ms"]
        for size, b in per["browser"].items():
            frames = f"{fmt(b['answer_frames']['dom']['p95'])} / {fmt(b['answer_frames']['scene']['p95'])}"
            lines.append(
                f"{mode:<5} {size:>9} {pair(b['answer_drawn_ms']['dom']):>18} {pair(b['answer_drawn_ms']['scene']):>10} "
                f"{frames:>21} {pair(b['drone_moving_ms']):>13} {pair(floor):>10} {fmt(b['fps_mean']):>5} "
                f"{fmt(b['frame_ms_median']):>8} {','.join(map(str, b['dpr_seen'])):>12} {fmt(b['pose_rate_hz_mean']):>7} "
                f"{fmt(b['server_cpu_pct']):>8} % {fmt(b['chromium_cpu_pct']):>10} %"
            )
    lines += [
        "",
        "legs of key → drone moving (p50 / p95, ms; host wall clock): keydown → /keydown published (input) → "
        "answering pose published (server) → in the pose worker (network) → in the main thread",
    ]
    for mode, per in results["modes"].items():
        for size, b in per["browser"].items():
            legs = b["legs_ms"]
            lines.append(
                f"{mode:<5} {size:>9}  "
                + "   ".join(f"{name} {pair(legs[name])} (n {legs[name]['n']})" for name in legs)
            )
            lines.append(
                f"{'':<5} {'':>9}  presses without an answer drawn {b['no_answer_drawn']}, without drone "
                f"motion {b['no_drone_motion']}; waits that ended unsettled {b['not_settled_before_next']}; "
                f"drone moving below the floor's minimum {len(b['below_in_process_min'])}"
            )
    lines += [
        "",
        "floor: key → drone moving in process on a ManualClock (physics and control only).",
        "frame ms: median main-thread cost of a drawn frame; CPU: % of one core over the press loop.",
    ]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--presses", type=int, default=60, help="browser presses per mode and window size")
    parser.add_argument("--trials", type=int, default=100, help="in-process presses per mode")
    parser.add_argument("--modes", nargs="+", default=["hold"], choices=sorted(HOLD_S))
    parser.add_argument("--viewports", nargs="+", default=["1000x650", "1366x768"], help="WIDTHxHEIGHT")
    args = parser.parse_args(argv)
    if not Path(CHROMIUM).is_file():
        print(f"no Chromium at {CHROMIUM}: apt-get install chromium", file=sys.stderr)
        return 2
    viewports = [tuple(int(v) for v in size.split("x")) for size in args.viewports]

    results: dict[str, Any] = {
        "when": datetime.now().astimezone().isoformat(timespec="seconds"),
        "machine": machine_info(),
        "load_avg_start": os.getloadavg(),
        "modes": {},
    }
    for mode in args.modes:
        print(f"{mode}: in process ({args.trials} presses on a ManualClock) ...", flush=True)
        per: dict[str, Any] = {"in_process": bench_in_process(mode, args.trials), "browser": {}}
        floor = per["in_process"]["latency_ms"]["min"]
        for width, height in viewports:
            print(f"{mode}: in Chromium at {width}x{height} ({args.presses} presses) ...", flush=True)
            b = bench_browser(mode, (width, height), args.presses)
            # Faster than physics allows: the drone was already swinging the key's way.
            b["below_in_process_min"] = [
                v for v in b["raw"]["drone_moving_ms"] if floor is not None and v < floor
            ]
            per["browser"][f"{width}x{height}"] = b
        results["modes"][mode] = per
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
