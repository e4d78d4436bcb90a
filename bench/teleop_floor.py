"""The floor under the page's key-to-motion latency: the same press and the same "drone answering"
criterion as web/src/lab/hud.ts, in process on a ManualClock (``Settings(lab=LabSettings(launch='fly', viewer=False))``),
stepped by hand in 0.5 ms steps after ``lab.keyboard.key_down``: the physics and control chain
alone, with no network, browser, rendering or scheduling. bench/teleop_latency.py reports it beside
what the page measures.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path
from typing import Any

import numpy as np

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))  # the app's packages live at the root

HOLD_S = {"lab": 0.0, "adopt": 0.0, "hold": 0.3}  # how long a press holds its key, by keyboard mode
ANSWER_TIMEOUT_S = 3.0  # the HUD itself gives up on a press after 3 s
STEP_S = 0.0005
TICK_S = 0.05  # lab mode's 20 Hz timer
WARMUP_S = 8.0  # the drone takes off to (0, 0, 3) and hovers
SETTLE_S = 2.5  # simulated settling between presses
MOTION_M = 0.02  # the HUD's criteria (web/src/lab/hud.ts)
TILT_RAD = math.radians(0.3)


def percentiles(values: list[float]) -> dict[str, float | None]:
    if not values:
        return {"p50": None, "p95": None, "min": None, "max": None, "n": 0}
    a = np.asarray(values)
    return {
        "p50": float(np.percentile(a, 50)),
        "p95": float(np.percentile(a, 95)),
        "min": float(a.min()),
        "max": float(a.max()),
        "n": len(values),
    }


def tilt_toward_x(q: Any) -> float:
    """web/src/lab/hud.ts's tiltToward(q, 0): the pitch that moves the drone towards +x."""
    return math.asin(max(-1.0, min(1.0, 2 * (q.w * q.y - q.z * q.x))))


def bench_in_process(mode: str, trials: int, seed: int = 1) -> dict[str, Any]:
    from node_runtime.bus import ManualClock
    from node_runtime.msgs import Key
    from server.host.settings import LabSettings, Settings
    from server.world.lab import Lab

    rng = np.random.default_rng(seed)
    lab = Lab(
        Settings(lab=LabSettings(launch="fly", viewer=False, launch_args={"keyboard_mode": mode})),
        ManualClock(0.0),
    )
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
    return {
        "trials": trials,
        "latency_ms": percentiles(latencies),
        "timed_out": timed_out,
        "step_ms": STEP_S * 1000,
    }
