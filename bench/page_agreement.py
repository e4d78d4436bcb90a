"""Does bench/page_client.py load a lab as a real page does? One headless Chromium page (Debian's
``chromium`` through Playwright, as the browser tests launch it) and one page client, both open
on the same lab in the same run, each counting messages a second per channel over the same
window; printed side by side with whether each channel agrees within 10 %.

    .venv/bin/python bench/page_agreement.py [--seconds 10] [--warm-s 8] [--launch fly]

The page's frames are read from Chromium's own WebSocket events (Playwright's ``websocket``:
frames received and sent), and viser's are decoded by the page client's own decoder, so both
sides count the same thing. The pose stream is opened by the page's Web Worker: where Chromium
does not report a worker's sockets to Playwright, those channels show as not seen on the page's
side (0), and the agreement is judged on the channels whose socket the page opened. Bounded: one server, one page,
``--warm-s + --seconds`` of counting (at most 120 s), then everything ends by its own id.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import shutil
import sys
import tempfile
import threading
import time
from pathlib import Path
from typing import Any
from urllib.parse import urlparse

sys.path.insert(0, str(Path(__file__).resolve().parent))
from live_server import LiveServer
from machine import machine_info, save_results
from page_client import POSE_TOPICS, Counts, PageClient

AGREE = 0.10
MAX_S = 120.0
CHROMIUM_ARGS = [
    "--headless=new",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
    "--disable-quic",
    "--use-angle=swiftshader",
    "--enable-unsafe-swiftshader",
    # A headless page counts as in the background, where Chromium slows its timers (the key
    # channel's heartbeat among them); a student's page is in front.
    "--disable-background-timer-throttling",
    "--disable-renderer-backgrounding",
    "--disable-backgrounding-occluded-windows",
]


class PageCounts:
    """The Chromium page's WebSocket frames, counted per channel as the page client counts them."""

    def __init__(self) -> None:
        self.counts = Counts()
        self.lock = threading.Lock()
        self.sockets: list[str] = []

    def watch(self, ws: Any) -> None:
        path = urlparse(ws.url).path
        self.sockets.append(path)
        pose = next((name for name, topic in POSE_TOPICS.items() if path == f"/ws/topics/{topic}"), None)

        def received(payload: str | bytes) -> None:
            with self.lock:
                if path == "/" and isinstance(payload, bytes):
                    self.counts.add_viser(payload)
                elif pose is not None:
                    self.counts.channels[pose] += 1
                elif path == "/ws/keys":
                    self.counts.channels["keys"] += 1

        def sent(payload: str | bytes) -> None:
            text = payload.decode(errors="replace") if isinstance(payload, bytes) else str(payload)
            if path == "/ws/keys" and "heartbeat" in text:
                with self.lock:
                    self.counts.channels["keys_sent"] += 1

        ws.on("framereceived", received)
        ws.on("framesent", sent)

    def restart(self) -> None:
        with self.lock:
            self.counts.restart()

    def rates(self) -> dict[str, float]:
        with self.lock:
            return self.counts.rates()


def channels_of(path: str) -> set[str]:
    """The channels a page's socket at ``path`` carries."""
    if path == "/":
        return {"viser_scene", "viser_gui", "viser_other"}
    if path == "/ws/keys":
        return {"keys", "keys_sent"}
    return {name for name, topic in POSE_TOPICS.items() if path == f"/ws/topics/{topic}"}


def compare(
    page: dict[str, float], client: dict[str, float], sockets: list[str]
) -> dict[str, dict[str, Any]]:
    """Per channel: both rates, and whether they agree within 10 % (None: the page opened no
    socket for it, so Playwright could not see its frames)."""
    opened = set().union(*(channels_of(path) for path in sockets)) if sockets else set()
    rows: dict[str, dict[str, Any]] = {}
    for name in sorted(set(page) | set(client)):
        p, c = page.get(name, 0.0), client.get(name, 0.0)
        agree = None if name not in opened else abs(c - p) <= AGREE * max(p, c)
        rows[name] = {"page_hz": round(p, 2), "client_hz": round(c, 2), "agree": agree}
    return rows


def run(seconds: float, warm_s: float, launch: str) -> dict[str, Any]:
    from playwright.sync_api import sync_playwright

    executable = shutil.which("chromium") or "/usr/bin/chromium"
    with tempfile.TemporaryDirectory() as tmp:
        server = LiveServer(Path(tmp), launch, "--no-foxglove")
        try:
            client = PageClient(server.url)
            thread_rates: dict[str, dict[str, float]] = {}

            def client_side() -> None:
                thread_rates["client"] = asyncio.run(client.run(seconds, warm_s))

            with sync_playwright() as playwright:
                browser = playwright.chromium.launch(executable_path=executable, args=CHROMIUM_ARGS)
                try:
                    page_counts = PageCounts()
                    context = browser.new_context(viewport={"width": 1000, "height": 650})
                    page = context.new_page()
                    page.on("websocket", page_counts.watch)
                    started = time.monotonic()
                    side = threading.Thread(target=client_side, daemon=True)
                    page.goto(server.url + "/")
                    page.bring_to_front()
                    side.start()
                    page.wait_for_timeout(warm_s * 1000)
                    page_counts.restart()
                    page.wait_for_timeout(seconds * 1000)
                    page_rates = page_counts.rates()
                    side.join(timeout=30)
                    elapsed = time.monotonic() - started
                finally:
                    browser.close()
            problems = server.log_problems()
        finally:
            server.stop()
    return {
        "channels": compare(page_rates, thread_rates.get("client", {}), page_counts.sockets),
        "page_sockets": sorted(set(page_counts.sockets)),
        "client_errors": client.errors,
        "elapsed_s": round(elapsed, 1),
        "log_problems": problems[:5],
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seconds", type=float, default=10.0, help="counting window, s")
    parser.add_argument("--warm-s", type=float, default=8.0, help="before counting: the page loads, s")
    parser.add_argument("--launch", default="fly")
    args = parser.parse_args(argv)
    if args.seconds + args.warm_s > MAX_S:
        parser.error(f"--seconds + --warm-s is at most {MAX_S:g}")
    info = machine_info()
    print(f"machine: {info['cpu_model']}, {info['nproc']} CPUs, Python {info['python']}", flush=True)
    result = run(args.seconds, args.warm_s, args.launch)
    print(f"{'channel':<14} {'page Hz':>9} {'client Hz':>10}  within 10 %")
    for name, row in result["channels"].items():
        verdict = "no such socket on the page" if row["agree"] is None else ("yes" if row["agree"] else "NO")
        print(f"{name:<14} {row['page_hz']:>9.2f} {row['client_hz']:>10.2f}  {verdict}")
    print("page sockets:", ", ".join(result["page_sockets"]), flush=True)
    if result["client_errors"] or result["log_problems"]:
        print("problems:", json.dumps(result["client_errors"] + result["log_problems"]))
    save_results(
        "page_agreement", {"machine": info, "seconds": args.seconds, "warm_s": args.warm_s, **result}
    )
    seen = [row["agree"] for row in result["channels"].values() if row["agree"] is not None]
    return 0 if seen and all(seen) else 1


if __name__ == "__main__":
    sys.exit(main())
