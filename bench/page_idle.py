"""What an open lab page costs while nothing happens in it: headless Chromium on software WebGL
(SwiftShader, as on a laptop without GPU acceleration), the page at 1366x768 on the quadrotor's
view with the follow camera, the drone hovering where it starts and the rocket waiting on its pad.

For each of ``--runs`` pages (each in a browser context of its own, one after the other): once the
page has drawn steadily, over ``--watch-s`` seconds, the CPU of Chromium's processes by kind
(browser, GPU process, renderers: cores, from /proc) and of the lab's server, and the frames the
page drew (its 3D view's renders). Each viser update makes the page draw its 3D view for a quarter
second, so a page at rest should draw about once a second.

    .venv/bin/python bench/page_idle.py --runs 3

Results: medians with the machine's details; JSON in bench/results/page_idle.json (git-ignored).
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from collections import Counter
from pathlib import Path
from typing import Any

from lab_browser import have_chromium, lab_and_chromium
from live_server import LiveServer
from machine import machine_info, save_results

VIEWPORT = {"width": 1366, "height": 768}
WAIT_MS = 90_000
SETTLE_S = 5.0  # after the scene is ready: the camera's first moves and the page's quality steps
TICKS = os.sysconf("SC_CLK_TCK")
READY_JS = (
    "() => window.__teleop !== undefined && window.__teleop.scene.ready && window.__teleop.keys.connected"
)
RENDERS_JS = "window.__teleop.scene.renders"
# The quadrotor's view, following the drone: a student's page flying it (the choice the page keeps).
VIEW_JS = "localStorage.setItem('teleop.view', 'Quadrotor'); localStorage.setItem('teleop.follow', 'follow');"


def chromium_ticks() -> Counter[str]:
    """CPU ticks so far of every Chromium process on the machine, by its --type (browser: none)."""
    out: Counter[str] = Counter()
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            argv = Path(f"/proc/{pid}/cmdline").read_bytes().split(b"\0")
            if not argv or b"chrom" not in argv[0]:
                continue
            kinds = [a[len(b"--type=") :].decode() for a in argv if a.startswith(b"--type=")]
            out[kinds[0] if kinds else "browser"] += process_ticks(int(pid))
        except (OSError, IndexError, ValueError):
            continue
    return out


def process_ticks(pid: int) -> int:
    stat = Path(f"/proc/{pid}/stat").read_text()
    fields = stat[stat.rfind(")") + 2 :].split()
    return int(fields[11]) + int(fields[12])


def snapshot(page: Any, server: LiveServer) -> tuple[Counter[str], int, int, float]:
    """Chromium's ticks by kind, the server's, the page's frames drawn, and when."""
    return chromium_ticks(), process_ticks(server.proc.pid), page.evaluate(RENDERS_JS), time.monotonic()


def one_page(browser: Any, server: LiveServer, watch_s: float) -> dict[str, Any]:
    context = browser.new_context(viewport=VIEWPORT)
    context.add_init_script(VIEW_JS)
    page = context.new_page()
    try:
        page.goto(server.url + "/", timeout=WAIT_MS)
        page.wait_for_function(READY_JS, polling=100, timeout=WAIT_MS)
        time.sleep(SETTLE_S)
        chrome0, server0, renders0, t0 = snapshot(page, server)
        time.sleep(watch_s)
        chrome1, server1, renders1, t1 = snapshot(page, server)
    finally:
        context.close()
    span = t1 - t0
    by_kind = {k: (chrome1[k] - chrome0.get(k, 0)) / TICKS / span for k in chrome1}
    return {
        "chromium_cores": sum(by_kind.values()),
        "chromium_cores_by_kind": {k: round(v, 3) for k, v in sorted(by_kind.items())},
        "server_cores": (server1 - server0) / TICKS / span,
        "frames_per_s": (renders1 - renders0) / span,
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--watch-s", type=float, default=20.0)
    args = parser.parse_args(argv)
    if not have_chromium():
        return 2
    results: dict[str, Any] = {"machine": machine_info(), "pages": []}
    with lab_and_chromium() as (server, browser):
        for i in range(args.runs):
            one = one_page(browser, server, args.watch_s)
            results["pages"].append(one)
            print(
                f"page {i + 1}: Chromium {one['chromium_cores']:.2f} cores "
                f"{one['chromium_cores_by_kind']}, server {one['server_cores']:.2f}, "
                f"{one['frames_per_s']:.1f} frames/s",
                flush=True,
            )
    pages, m = results["pages"], results["machine"]
    print(f"\nmachine: {m['nproc']} CPU(s), {m['cpu_model']}; Python {m['python']}")
    for key in ("chromium_cores", "server_cores", "frames_per_s"):
        print(f"  median {key:<15} {statistics.median(p[key] for p in pages):6.2f}")
    save_results("page_idle", results)
    return 0


if __name__ == "__main__":
    sys.exit(main())
