"""How long the lab page takes to load in headless Chromium on software WebGL (SwiftShader, as on a
machine without GPU acceleration), and how long its main thread stalls while it does.

One server (``--launch all``, the rocket waiting), one Chromium; ``--loads`` pages one after the
other, each in a browser context of its own, as a student's first visit. For each load: the
phases (navigation; viser connected; the key channel open; the scene ready; a steady frame rate,
that is 20 frames drawn and none over 400 ms apart for 2 s, which the browser tests wait for) and,
over the first ``--watch-s`` seconds, the longest gap between two animation frames (the main
thread busy: a key pressed then waits as long) and the gaps over 400 ms.

    .venv/bin/python bench/page_load.py --loads 5

Results: medians with the machine's details; JSON in bench/results/page_load.json (git-ignored).
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from typing import Any

from lab_browser import have_chromium, lab_and_chromium
from machine import machine_info, save_results

VIEWPORT = {"width": 1000, "height": 650}  # the browser tests' page
WAIT_MS = 90_000
STALL_MS = 400
# Every gap between two animation frames, from the page's first script on.
GAPS_JS = """(() => { const m = { t0: performance.now(), last: performance.now(), gaps: [] };
  window.__gaps = m;
  const tick = (now) => { m.gaps.push([now - m.t0, now - m.last]); m.last = now; requestAnimationFrame(tick); };
  requestAnimationFrame(tick); })();"""
STEADY_JS = f"""() => {{ const g = window.__gaps.gaps; const now = performance.now() - window.__gaps.t0;
  return g.length > 20 && g.every(([t, d]) => t < now - 2000 || d <= {STALL_MS}); }}"""
PHASES = [
    ("connected", "() => document.body.innerText.includes('Connected')"),
    ("keys", "() => window.__teleop !== undefined && window.__teleop.keys.connected"),
    ("scene", "() => window.__teleop !== undefined && window.__teleop.scene.ready"),
    ("steady", STEADY_JS),
]


def one_load(browser: Any, url: str, watch_s: float) -> dict[str, Any]:
    context = browser.new_context(viewport=VIEWPORT)
    context.add_init_script(GAPS_JS)
    page = context.new_page()
    try:
        start = time.monotonic()
        page.goto(url + "/", timeout=WAIT_MS)
        phases = {"navigation": time.monotonic() - start}
        for name, ready in PHASES:
            page.wait_for_function(ready, polling=100, timeout=WAIT_MS)
            phases[name] = time.monotonic() - start
        time.sleep(max(0.0, watch_s - (time.monotonic() - start)))
        gaps = page.evaluate("window.__gaps.gaps")
    finally:
        context.close()
    return {
        "phases_s": phases,
        "longest_gap_ms": max(d for _, d in gaps),
        "stalls": [[round(t), round(d)] for t, d in gaps if d > STALL_MS],
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--loads", type=int, default=5)
    parser.add_argument(
        "--watch-s", type=float, default=15.0, help="how long each page is watched for stalls"
    )
    args = parser.parse_args(argv)
    if not have_chromium():
        return 2
    results: dict[str, Any] = {"machine": machine_info(), "loads": []}
    with lab_and_chromium() as (server, browser):
        for i in range(args.loads):
            load = one_load(browser, server.url, args.watch_s)
            results["loads"].append(load)
            print(
                f"load {i + 1}: steady at {load['phases_s']['steady']:.1f} s, "
                f"longest stall {load['longest_gap_ms']:.0f} ms",
                flush=True,
            )
    loads = results["loads"]
    m = results["machine"]
    print(f"\nmachine: {m['nproc']} CPU(s), {m['cpu_model']}; Python {m['python']}")
    print(f"median of {len(loads)} loads (seconds from navigation):")
    for name in ["navigation", *(n for n, _ in PHASES)]:
        print(f"  {name:<11} {statistics.median(load['phases_s'][name] for load in loads):6.1f} s")
    print(f"  longest stall {statistics.median(load['longest_gap_ms'] for load in loads):6.0f} ms")
    save_results("page_load", results)
    return 0


if __name__ == "__main__":
    sys.exit(main())
