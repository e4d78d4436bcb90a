"""For the browser tests: the lab page in a headless Chromium, and the server's topics it is checked
against. Every wait is bounded: Playwright's own timeouts, or a polled deadline."""

from __future__ import annotations

import contextlib
import math
import time
import warnings
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest
from labserver import LabServer
from playwright.sync_api import Browser, Page
from playwright.sync_api import Error as PlaywrightError
from support.http import HTTP
from support.wait import wait_until as support_wait_until

WAIT_S = 15.0
STILL_M_S = 0.1
STILL_WINDOW_S = 0.5
STILL_DRIFT_M = 0.05
STILL_SIM_WAIT_S = 10.0  # for the sim to run a STILL_WINDOW_S of its own (a starved world lags)
# The drone stops in about 1.5 s, but each check is 4 requests, and a loaded 2-core machine (a
# page drawing in software beside the server) answered each in 0.4-4 s.
STOP_WAIT_S = 30.0
HTTP_TIMEOUT_S = 30.0
PAGE_WAIT_MS = 30_000
LOAD_WAIT_MS = 90_000  # a first load parses viser's bundle; on a 2-core machine with a busy neighbour
SETTLE_WAIT_MS = 25_000
CLICK_WAIT_MS = 2_000
MAX_NOTIFICATIONS = 5
VIEWPORT = {"width": 1000, "height": 650}

# Counts requestAnimationFrame frames and remembers the last long gap between two: SwiftShader
# stalls the page's main thread for seconds while it compiles the scene's shaders, a few seconds
# after load, and a stall during a hold would stop the heartbeats (the dead-man then releases).
FRAME_MONITOR_JS = """(() => {
  const m = { count: 0, last: performance.now(), lastStall: performance.now() };
  window.__frames = m;
  const tick = (now) => { if (now - m.last > 400) m.lastStall = now; m.last = now; m.count++;
    requestAnimationFrame(tick); };
  requestAnimationFrame(tick);
})();"""
SETTLED_JS = "() => window.__frames.count > 20 && performance.now() - window.__frames.lastStall > 2000"


# -- the server's topics -------------------------------------------------------------------------
def wait_until(check: Callable[[], Any], what: str, timeout_s: float = WAIT_S, poll_s: float = 0.05) -> Any:
    """support.wait's wait, with the browser tests' longer default (a page drawing beside the server)."""
    return support_wait_until(check, what, timeout_s, poll_s=poll_s)


def topic(server: LabServer, name: str) -> dict[str, Any]:
    response = HTTP.get(f"{server.url}/api/topics/{name.lstrip('/')}", timeout=HTTP_TIMEOUT_S)
    response.raise_for_status()
    return response.json()


def position(server: LabServer) -> tuple[float, float, float]:
    p = topic(server, "/uav/sensors/gps")["latest"]["pose"]["position"]
    return p["x"], p["y"], p["z"]


def still(read: Callable[[str], dict[str, Any]]) -> tuple[float, float, float] | None:
    """Where the drone is if it is still, else None; ``read`` answers a topic as GET /api/topics does.

    Still: under 0.1 m/s at both ends of a window, and two GPS fixes at least 0.5 s apart *on the
    sim's clock* (their stamps) within 5 cm. The window is the sim's, not the test's: a world
    starved of CPU can publish late, and two readings half a second apart on the wall clock may
    then hold the same fix, or two a few ticks apart, while the drone is still braking."""

    def fix() -> tuple[tuple[float, float, float], float]:
        pose = read("/uav/sensors/gps")["latest"]
        p, stamp = pose["pose"]["position"], pose["header"]["stamp"]
        return (p["x"], p["y"], p["z"]), stamp["sec"] + stamp["nanosec"] * 1e-9

    def slow() -> bool:
        v = read("/uav/sensors/velocity")["latest"]["twist"]["linear"]
        return math.hypot(v["x"], v["y"], v["z"]) < STILL_M_S

    if not slow():
        return None
    before, t0 = fix()
    time.sleep(STILL_WINDOW_S)
    after, t1 = fix()
    give_up = time.monotonic() + STILL_SIM_WAIT_S
    while t1 - t0 < STILL_WINDOW_S:  # the sim has not yet run the window: read again a little later
        if time.monotonic() > give_up:
            return None
        time.sleep(STILL_WINDOW_S / 5)
        after, t1 = fix()
    return after if math.dist(before, after) < STILL_DRIFT_M and slow() else None


def wait_stopped(server: LabServer, timeout_s: float = STOP_WAIT_S) -> tuple[float, float, float]:
    """Until the drone is still (``still``); where."""
    return wait_until(lambda: still(lambda name: topic(server, name)), "the drone to stop", timeout_s)


# -- the page ------------------------------------------------------------------------------------
@contextlib.contextmanager
def lab_page(chromium: Browser, viewport: dict[str, int] | None = None) -> Iterator[Page]:
    """A page (1000x650 unless told) in its own context, counting its frames; uncaught page errors
    fail the test."""
    context = chromium.new_context(viewport=viewport or VIEWPORT)
    context.add_init_script(FRAME_MONITOR_JS)
    page = context.new_page()
    page.set_default_timeout(PAGE_WAIT_MS)
    errors: list[str] = []
    page.on("pageerror", lambda exc: errors.append(str(exc)))
    try:
        yield page
    finally:
        context.close()
    assert errors == [], f"uncaught errors in the page: {errors}"


def open_lab_page(
    page: Page, server: LabServer | None, close_notices: bool = True, settle_ms: int = SETTLE_WAIT_MS
) -> None:
    """Load the lab page (``server`` None: the page is loading already, e.g. after a class
    server's join form); wait for viser, the key channel, the page's camera view and (up to
    ``settle_ms``; 0: not at all) a steady frame rate; close viser's notifications unless told
    not to."""
    if server is not None:
        page.goto(server.url + "/", timeout=LOAD_WAIT_MS)
    page.wait_for_function("() => document.body.innerText.includes('Connected')", timeout=LOAD_WAIT_MS)
    page.wait_for_function(
        "() => window.__teleop !== undefined && window.__teleop.keys.connected", timeout=LOAD_WAIT_MS
    )
    page.wait_for_function(
        "() => window.__teleop !== undefined && window.__teleop.scene.ready", timeout=LOAD_WAIT_MS
    )
    try:
        if settle_ms:
            page.wait_for_function(SETTLED_JS, polling=100, timeout=settle_ms)
    except PlaywrightError:
        warnings.warn(f"the page never drew steadily for 2 s within {settle_ms} ms; going on", stacklevel=2)
    if not close_notices:
        return
    close_buttons = page.locator(".mantine-Notification-closeButton")
    for _ in range(MAX_NOTIFICATIONS):
        if not close_buttons.count():
            break
        with contextlib.suppress(PlaywrightError):  # it may be closing already
            close_buttons.first.click(timeout=CLICK_WAIT_MS)


def wait_frames(page: Page, frames: int = 5) -> None:
    """Let the page draw a few more frames (after a camera move or a state change)."""
    start = page.evaluate("window.__frames.count")
    page.wait_for_function(f"() => window.__frames.count >= {start + frames}", polling="raf")


def save_screenshot(page: Page, folder: Path, name: str, capsys: pytest.CaptureFixture[str]) -> bytes:
    png = page.screenshot()
    (folder / name).write_bytes(png)
    with capsys.disabled():
        print(f"\nscreenshot {name} in {folder}")
    return png
