"""Keyboard teleop and the page's tools in a real headless Chromium, against ``python -m server``.

Hold mode (``--launch fly keyboard_mode:=hold``): holding → the drone moves, releasing → it
stops; and every way a hold can end without a keyup ends it on the server: a blur (the page
sends ``release_all``), a closed or crashed page (the channel closes), a frozen page (the
server's dead-man timer). The Message Publisher panel flies the drone to (5, 5, 10) at 1 Hz.
Screenshots are checked for what their names say by colour classes in the 3D canvas.

Chromium, the server subprocess and the rocket abort test live in conftest.py, labserver.py and
test_rocket_browser.py. Every wait is bounded: Playwright's own timeouts, or a polled deadline.
The ``time.sleep`` calls here are key-hold durations and observation windows, not waits.
"""

from __future__ import annotations

import contextlib
import io
import itertools
import math
import os
import re
import signal
import time
import warnings
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import httpx
import numpy as np
import pytest
from labserver import LabServer
from PIL import Image
from playwright.sync_api import Browser, Page
from playwright.sync_api import Error as PlaywrightError

pytestmark = pytest.mark.browser

KEY_RIGHT = 275  # keyboard_msgs/Key code (SDL) of ArrowRight
HOME_M = (0.0, 0.0, 3.0)  # the keyboard manager's start setpoint
HOLD_S = 1.0
BRIEF_HOLD_S = 0.3
MOVED_M = 0.5  # hold speed 2 m/s for 1 s moves about 2 m; far more than hover jitter
# How far a hold may take the drone: hold speed 2 m/s (2.2 m/s seen) for as long as the server
# saw the key held, plus the stop: the brake setpoint (0.55 s of velocity ahead) and overshoot.
MAX_HOLD_SPEED_M_S = 2.5
STOP_M = 1.5
STILL_M_S = 0.1
STILL_WINDOW_S = 0.5
STILL_DRIFT_M = 0.05
STOP_WAIT_S = 10.0  # the drone stops in about 1.5 s; generous for a loaded 2-core machine
RELEASE_WAIT_S = 3.0  # a release must reach /keyup well inside this (dead-man: 0.5 s)
HOME_WAIT_S = 25.0
FLIGHT_WAIT_S = 30.0
ARRIVED_M = 0.1
WAIT_S = 15.0
PAGE_WAIT_MS = 30_000
SETTLE_WAIT_MS = 25_000
CLICK_WAIT_MS = 2_000
MAX_NOTIFICATIONS = 5
VIEWPORT = {"width": 1000, "height": 650}
DEADMAN_LOG = "silent for over"  # api/ws_keys.py logs this when its timer releases keys

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
    """Poll ``check`` until it returns something truthy (returned); fail after ``timeout_s``."""
    deadline = time.monotonic() + timeout_s
    while not (value := check()):
        if time.monotonic() > deadline:
            pytest.fail(f"gave up after {timeout_s} s waiting for {what} (last: {value!r})")
        time.sleep(poll_s)
    return value


def topic(server: LabServer, name: str) -> dict[str, Any]:
    response = httpx.get(f"{server.url}/api/topics/{name.lstrip('/')}", timeout=5.0)
    response.raise_for_status()
    return response.json()


def position(server: LabServer) -> tuple[float, float, float]:
    p = topic(server, "/uav/sensors/gps")["latest"]["pose"]["position"]
    return p["x"], p["y"], p["z"]


def speed(server: LabServer) -> float:
    v = topic(server, "/uav/sensors/velocity")["latest"]["twist"]["linear"]
    return math.hypot(v["x"], v["y"], v["z"])


def wait_stopped(server: LabServer, timeout_s: float = STOP_WAIT_S) -> tuple[float, float, float]:
    """Until the drone is still (under 0.1 m/s, and two positions 0.5 s apart within 5 cm); where."""

    def still() -> tuple[float, float, float] | None:
        if speed(server) >= STILL_M_S:
            return None
        before = position(server)
        time.sleep(STILL_WINDOW_S)
        after = position(server)
        return after if math.dist(before, after) < STILL_DRIFT_M and speed(server) < STILL_M_S else None

    return wait_until(still, "the drone to stop", timeout_s)


def fly_home(server: LabServer) -> tuple[float, float, float]:
    """Publish the start setpoint (every keyboard mode but lab adopts it) and wait until it is held."""
    body = {"topic": "/uav/input/position", "msg": dict(zip("xyz", HOME_M, strict=True))}
    assert httpx.post(f"{server.url}/api/publish", json=body, timeout=5.0).status_code == 200
    wait_until(lambda: math.dist(position(server), HOME_M) < 0.15, "the drone back at (0, 0, 3)", HOME_WAIT_S)
    return wait_stopped(server)


def keyup_count(server: LabServer) -> int:
    return topic(server, "/keyup")["publish_count"]


def wait_keyup(server: LabServer, count_before: int, code: int = KEY_RIGHT) -> dict[str, Any]:
    """Until /keyup has a new message, for ``code``; returns the topic."""

    def released() -> dict[str, Any] | None:
        keyup = topic(server, "/keyup")
        latest = keyup["latest"]
        return keyup if keyup["publish_count"] > count_before and latest and latest["code"] == code else None

    return wait_until(released, f"a keyup of code {code} on /keyup", RELEASE_WAIT_S, poll_s=0.02)


def deadman_releases(server: LabServer) -> int:
    return server.log_tail(10**7).count(DEADMAN_LOG)


# -- the page ------------------------------------------------------------------------------------
@contextlib.contextmanager
def lab_page(chromium: Browser) -> Iterator[Page]:
    """A 1000x650 page in its own context, counting its frames; uncaught page errors fail the test."""
    context = chromium.new_context(viewport=VIEWPORT)
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


@pytest.fixture
def page(chromium: Browser) -> Iterator[Page]:
    with lab_page(chromium) as page:
        yield page


def open_lab_page(page: Page, server: LabServer) -> None:
    """Load the lab page; wait for viser, the key channel and a steady frame rate; close notifications."""
    page.goto(server.url + "/")
    page.wait_for_function("() => document.body.innerText.includes('Connected')")
    page.wait_for_function("() => window.__teleopKeys !== undefined && window.__teleopKeys.connected")
    try:
        page.wait_for_function(SETTLED_JS, polling=100, timeout=SETTLE_WAIT_MS)
    except PlaywrightError:
        warnings.warn(
            f"the page never drew steadily for 2 s within {SETTLE_WAIT_MS} ms; going on", stacklevel=2
        )
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


# -- what a screenshot shows ---------------------------------------------------------------------
# Colour classes rather than distances to the scene's nominal colours: SwiftShader shades the hub
# from (0, 120, 0) to (120, 230, 120), and viser draws line segments lighter than given: the blue
# arm (30, 60, 255) comes out about (118, 149, 226), the red one (230, 30, 30) about (238, 114, 107).
GIZMO_PX = 100  # viser's axes gizmo (red, green and blue) in the canvas's bottom-left corner
MIN_HUB_PX, MIN_BLUE_ARM_PX, MIN_RED_ARM_PX = 15, 15, 4  # seen: 42-50, 46-48, 8-26
ARM_REACH_PX = 80  # the arms' pixels lie this close to the hub's centroid at the views' distances
MOVED_PX = 20

# The 3D canvas's rectangle, and which of its points (on a grid of SAMPLE_PX) show the canvas
# itself: not viser's control panel or a 3D label floating over it, nor one of our overlays
# (the HUD and the key badge let the pointer through, so elementFromPoint does not see them).
SAMPLE_PX = 4
SCENE_POINTS_JS = """(step) => {
  const canvas = [...document.querySelectorAll('canvas')].sort((a, b) => b.width * b.height - a.width * a.height)[0];
  const box = canvas.getBoundingClientRect();
  // viser stacks a pointer-catching canvas of the same size over the WebGL one.
  const isScene = (e) => { if (!e || e.tagName !== 'CANVAS') return false; const r = e.getBoundingClientRect();
    return Math.abs(r.left - box.left) < 1 && Math.abs(r.top - box.top) < 1 && Math.abs(r.width - box.width) < 1; };
  const ours = [...document.querySelectorAll('[id^="teleop-"]')].map((e) => e.getBoundingClientRect());
  const cols = Math.ceil(box.width / step), rows = Math.ceil(box.height / step);
  let shown = '';
  for (let j = 0; j < rows; j++) for (let i = 0; i < cols; i++) {
    const x = box.left + (i + 0.5) * step, y = box.top + (j + 0.5) * step;
    const hidden = !isScene(document.elementFromPoint(x, y))
      || ours.some((r) => x >= r.left && x <= r.right && y >= r.top && y <= r.bottom);
    shown += hidden ? '0' : '1';
  }
  return { box: [box.left, box.top, box.width, box.height], cols, rows, shown };
}"""


@dataclass(frozen=True)
class CanvasShot:
    """The 3D canvas's part of a screenshot, and which of its pixels show the scene."""

    rgb: np.ndarray  # H x W x 3, int16 (so channel differences do not wrap)
    scene: np.ndarray  # H x W bool: not under the GUI or an overlay (HUD, key badge), nor viser's gizmo

    @classmethod
    def of(cls, page: Page, png: bytes) -> CanvasShot:
        layout = page.evaluate(SCENE_POINTS_JS, SAMPLE_PX)
        image = np.asarray(Image.open(io.BytesIO(png)).convert("RGB")).astype(np.int16)
        x, y, w, h = (round(v) for v in layout["box"])
        rgb = image[y : y + h, x : x + w]
        grid = np.frombuffer(layout["shown"].encode(), dtype=np.uint8).reshape(
            layout["rows"], layout["cols"]
        ) == ord("1")
        scene = np.repeat(np.repeat(grid, SAMPLE_PX, axis=0), SAMPLE_PX, axis=1)[
            : rgb.shape[0], : rgb.shape[1]
        ]
        scene[-GIZMO_PX:, :GIZMO_PX] = False
        return cls(rgb, scene)

    def mask(self, colour_class: Callable[[np.ndarray, np.ndarray, np.ndarray], np.ndarray]) -> np.ndarray:
        r, g, b = self.rgb[..., 0], self.rgb[..., 1], self.rgb[..., 2]
        return colour_class(r, g, b) & self.scene


def hub_green(r: np.ndarray, g: np.ndarray, b: np.ndarray) -> np.ndarray:
    return (g >= 90) & (g - r >= 60) & (g - b >= 60)


def arm_blue(r: np.ndarray, g: np.ndarray, b: np.ndarray) -> np.ndarray:
    return (b >= 150) & (b - r >= 60) & (b - g >= 40)


def red(r: np.ndarray, g: np.ndarray, b: np.ndarray) -> np.ndarray:
    return (r >= 120) & (r - g >= 70) & (r - b >= 50)


def rocket_white(r: np.ndarray, g: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The body (235, 235, 240), shaded: light, grey, and not the page's white background."""
    hi, lo = np.maximum(np.maximum(r, g), b), np.minimum(np.minimum(r, g), b)
    return (lo >= 140) & (hi <= 245) & (hi - lo <= 35)


def pad_grey(r: np.ndarray, g: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The pad (110, 110, 120), shaded from about (68, 67, 82) to (110, 110, 127)."""
    hi, lo = np.maximum(np.maximum(r, g), b), np.minimum(np.minimum(r, g), b)
    return (lo >= 40) & (hi <= 150) & (hi - lo <= 35)


def largest_blob(mask: np.ndarray) -> np.ndarray:
    """The (row, column) pixels of the largest 8-connected region of ``mask``."""
    left = {(int(r), int(c)) for r, c in zip(*np.nonzero(mask), strict=True)}
    best: list[tuple[int, int]] = []
    while left:
        stack, blob = [left.pop()], []
        while stack:
            r, c = stack.pop()
            blob.append((r, c))
            for n in ((r + dr, c + dc) for dr in (-1, 0, 1) for dc in (-1, 0, 1)):
                if n in left:
                    left.remove(n)
                    stack.append(n)
        best = max(best, blob, key=len)
    return np.array(best, dtype=float).reshape(-1, 2)


@dataclass(frozen=True)
class DroneSeen:
    hub_px: int
    blue_px: int  # blue-arm pixels within ARM_REACH_PX of the hub
    red_px: int
    centre: tuple[float, float]  # the hub's centroid (column, row) in canvas pixels; rows grow downwards


def find_drone(shot: CanvasShot) -> DroneSeen:
    hub = largest_blob(shot.mask(hub_green))
    if not len(hub):
        return DroneSeen(0, 0, 0, (math.nan, math.nan))
    row, col = hub.mean(axis=0)
    rows, cols = np.indices(shot.scene.shape)
    near = (rows - row) ** 2 + (cols - col) ** 2 <= ARM_REACH_PX**2
    blue, red_ = int((shot.mask(arm_blue) & near).sum()), int((shot.mask(red) & near).sum())
    return DroneSeen(len(hub), blue, red_, (float(col), float(row)))


def assert_drone_seen(seen: DroneSeen, name: str) -> None:
    assert seen.hub_px >= MIN_HUB_PX, f"{name}: no green hub ({seen})"
    assert seen.blue_px >= MIN_BLUE_ARM_PX, f"{name}: no blue arm by the hub ({seen})"
    assert seen.red_px >= MIN_RED_ARM_PX, f"{name}: no red arm by the hub ({seen})"


MIN_NOSE_ROWS, MIN_BODY_ROWS, MIN_PAD_ROWS = 4, 15, 3
MAX_GAP_ROWS = 3  # anti-aliased edges between two parts
MIN_ROCKET_COLUMNS = 3
FIN_REACH_PX = 30
MIN_FIN_PX = 3


def rocket_columns(shot: CanvasShot) -> dict[int, tuple[int, int]]:
    """Columns that read, top to bottom, red nose → white body → grey pad (a rocket standing on
    it), each with its body's first and last row."""
    labels = np.zeros(shot.scene.shape, dtype=np.int8)  # 0 other, 1 red, 2 white, 3 pad
    labels[shot.mask(red)] = 1
    labels[shot.mask(rocket_white)] = 2
    labels[shot.mask(pad_grey)] = 3
    wanted = [(1, MIN_NOSE_ROWS), (2, MIN_BODY_ROWS), (3, MIN_PAD_ROWS)]
    found = {}
    for col in range(labels.shape[1]):
        runs: list[list[int]] = []  # [label, first row, rows], top to bottom, thin gaps dropped
        row = 0
        for label, group in itertools.groupby(labels[:, col].tolist()):
            rows = len(list(group))
            if runs and runs[-1][0] == label:
                runs[-1][2] = row + rows - runs[-1][1]
            elif label or rows > MAX_GAP_ROWS:  # a thin gap is an anti-aliased edge between parts
                runs.append([label, row, rows])
            row += rows
        for i in range(len(runs) - 2):
            if all(
                runs[i + k][0] == label and runs[i + k][2] >= rows for k, (label, rows) in enumerate(wanted)
            ):
                found[col] = (runs[i + 1][1], runs[i + 1][1] + runs[i + 1][2] - 1)
                break
    return found


def assert_rocket_on_pad(shot: CanvasShot, name: str) -> None:
    """A red nose over a white body on the grey pad, and red fins on both sides of the body's foot."""
    columns = rocket_columns(shot)
    assert len(columns) >= MIN_ROCKET_COLUMNS, f"{name}: no column reads nose → body → pad ({columns})"
    axis = int(np.median(list(columns)))
    top, bottom = columns[min(columns, key=lambda c: abs(c - axis))]
    foot = slice(max(bottom - (bottom - top) * 2 // 5, 0), bottom + 4)  # fins: the lowest fifth of the rocket
    reds = shot.mask(red)
    left = int(reds[foot, max(axis - FIN_REACH_PX, 0) : axis - 3].sum())
    right = int(reds[foot, axis + 4 : axis + FIN_REACH_PX].sum())
    assert left >= MIN_FIN_PX and right >= MIN_FIN_PX, (
        f"{name}: no fins on both sides (left {left}, right {right} px)"
    )


# -- hold mode -----------------------------------------------------------------------------------
@pytest.fixture(scope="class")
def hold_server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[LabServer]:
    """The drone lab with the keyboard manager in hold mode (hold a key to move)."""
    server = LabServer(
        ["--launch", "fly", "keyboard_mode:=hold"], tmp_path_factory.mktemp("hold") / "server.log"
    )
    try:
        server.wait_ready()
        yield server
    finally:
        server.stop()


@pytest.fixture(scope="class")
def hold_page(chromium: Browser, hold_server: LabServer) -> Iterator[Page]:
    """One hold-mode lab page for the tests that leave it open (loading one costs 10-30 s here)."""
    with lab_page(chromium) as page:
        open_lab_page(page, hold_server)
        yield page


@pytest.fixture
def home(hold_server: LabServer) -> tuple[float, float, float]:
    """The drone still at (0, 0, 3) before the test; where it is."""
    return fly_home(hold_server)


def renderer_pids() -> set[int]:
    """Chromium renderer processes started by this test process (Playwright's driver is its child)."""
    children: dict[int, list[int]] = {}
    for entry in Path("/proc").iterdir():
        with contextlib.suppress(OSError, ValueError, IndexError):
            ppid = int((entry / "stat").read_text().rsplit(")", 1)[1].split()[1])
            children.setdefault(ppid, []).append(int(entry.name))
    found, stack = set(), [os.getpid()]
    while stack:
        for pid in children.get(stack.pop(), []):
            stack.append(pid)
            with contextlib.suppress(OSError):
                # A zygote's child rewrites its argv into one string: search the whole command line.
                cmdline = (Path("/proc") / str(pid) / "cmdline").read_bytes()
                if b"--type=renderer" in cmdline and b"--top-chrome-webui" not in cmdline:
                    found.add(pid)
    return found


def held_for_s(server: LabServer) -> float:
    """How long the server saw the key held: from the latest /keydown to the latest /keyup."""
    down, up = (topic(server, name)["latest"]["header"]["stamp"] for name in ("/keydown", "/keyup"))
    return (up["sec"] - down["sec"]) + (up["nanosec"] - down["nanosec"]) * 1e-9


def assert_stopped_promptly(server: LabServer, x0: float) -> float:
    """The drone stops, to the right of where it started and not far past where the hold took it."""
    x = wait_stopped(server)[0]
    reach = x0 + MAX_HOLD_SPEED_M_S * held_for_s(server) + STOP_M
    assert x0 < x < reach, f"stopped at x = {x:.2f} m, from {x0:.2f} m (at most {reach:.2f} m)"
    return x


@pytest.mark.usefixtures("home")
class TestHoldMode:
    def test_hold_arrow_right_for_1s_moves_drone_right_and_release_stops_it(
        self, hold_page: Page, hold_server: LabServer
    ) -> None:
        x0, y0, z0 = position(hold_server)
        before = keyup_count(hold_server)
        hold_page.keyboard.down("ArrowRight")
        time.sleep(HOLD_S)  # the hold itself
        x_held = position(hold_server)[0]
        hold_page.keyboard.up("ArrowRight")
        assert x_held - x0 > MOVED_M
        wait_keyup(hold_server, before)
        x = assert_stopped_promptly(hold_server, x0)
        assert x > x_held - STILL_DRIFT_M  # it brakes ahead, it does not come back
        _, y, z = position(hold_server)
        assert abs(y - y0) < 0.3 and abs(z - z0) < 0.3  # moving along x keeps y and the height

    def test_blur_during_hold_releases_key_from_page_and_drone_stops(
        self, hold_page: Page, hold_server: LabServer
    ) -> None:
        x0 = position(hold_server)[0]
        before, deadman_before = keyup_count(hold_server), deadman_releases(hold_server)
        hold_page.keyboard.down("ArrowRight")
        time.sleep(BRIEF_HOLD_S)  # the hold itself
        # Headless Chromium never loses focus (another page brought to front does not blur this
        # one), so the window gets the event a real focus loss fires.
        hold_page.evaluate("window.dispatchEvent(new Event('blur'))")
        wait_keyup(hold_server, before)
        assert hold_page.evaluate("window.__teleopKeys.held.size") == 0
        assert_stopped_promptly(hold_server, x0)
        assert deadman_releases(hold_server) == deadman_before, "released by the dead-man, not by the page"
        hold_page.keyboard.up("ArrowRight")  # Playwright's own key state; the server ignores it

    def test_frozen_page_during_hold_dead_man_releases_key_and_drone_stops(
        self, hold_page: Page, hold_server: LabServer
    ) -> None:
        x0 = position(hold_server)[0]
        before, deadman_before = keyup_count(hold_server), deadman_releases(hold_server)
        cdp = hold_page.context.new_cdp_session(hold_page)
        paused: list[Any] = []
        cdp.on("Debugger.paused", lambda event: paused.append(event))
        cdp.send("Debugger.enable")
        hold_page.keyboard.down("ArrowRight")
        time.sleep(BRIEF_HOLD_S)  # the hold itself
        cdp.send("Debugger.pause")  # no more heartbeats, while the page's WebSocket stays open
        try:
            deadline = time.monotonic() + WAIT_S
            while not paused and time.monotonic() < deadline:
                hold_page.wait_for_timeout(20)  # lets Playwright deliver the CDP event
            assert paused, "the page's JavaScript did not pause"
            keyup = wait_keyup(hold_server, before)
            assert keyup["publish_count"] == before + 1
            assert deadman_releases(hold_server) == deadman_before + 1, hold_server.log_tail()
            assert_stopped_promptly(hold_server, x0)  # still frozen: the server alone stopped it
        finally:
            cdp.send("Debugger.resume")
            cdp.detach()
        # The page never released the key, and its channel was never closed.
        assert hold_page.evaluate("[...window.__teleopKeys.held]") == ["ArrowRight"]
        assert hold_page.evaluate("window.__teleopKeys.connected") is True
        hold_page.keyboard.up("ArrowRight")

    @pytest.mark.parametrize("end", ["close", "crash"])
    def test_page_gone_during_hold_server_releases_key_and_drone_stops(
        self, chromium: Browser, hold_server: LabServer, end: str
    ) -> None:
        renderers_before = renderer_pids()
        with lab_page(chromium) as page:
            open_lab_page(page, hold_server)
            x0 = position(hold_server)[0]
            before, deadman_before = keyup_count(hold_server), deadman_releases(hold_server)
            page.keyboard.down("ArrowRight")
            time.sleep(BRIEF_HOLD_S)  # the hold itself
            if end == "close":
                page.close()  # pagehide (the page sends release_all), then the channel closes
            else:
                with page.expect_event("crash", timeout=PAGE_WAIT_MS):
                    for pid in renderer_pids() - renderers_before:  # this page's (and maybe a spare)
                        os.kill(pid, signal.SIGKILL)  # no pagehide, no release_all: the channel drops
            wait_keyup(hold_server, before)
            assert_stopped_promptly(hold_server, x0)
            assert deadman_releases(hold_server) == deadman_before, "released by the dead-man timer"


# -- the rocket on its pad -----------------------------------------------------------------------
@pytest.fixture
def quiet_rocket_server(tmp_path: Path) -> Iterator[LabServer]:
    """The rocket lab with a countdown that starts a minute after launch: on the pad for the test."""
    server = LabServer(["--launch", "rocket", "start_delay:=60"], tmp_path / "server.log")
    try:
        server.wait_ready()
        yield server
    finally:
        server.stop()


def test_rocket_view_before_launch_shows_rocket_standing_on_pad(
    page: Page, quiet_rocket_server: LabServer, screenshot_dir: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    open_lab_page(page, quiet_rocket_server)
    page.get_by_role("button", name="Rocket", exact=True).click()
    wait_frames(page)
    png = save_screenshot(page, screenshot_dir, "rocket_on_pad.png", capsys)
    text = page.evaluate("document.body.innerText")
    assert re.search(r"Ready|Counting down", text), text[:500]
    assert_rocket_on_pad(CanvasShot.of(page, png), "rocket_on_pad.png")


# -- the Message Publisher panel -----------------------------------------------------------------
@pytest.fixture
def fly_server(tmp_path: Path) -> Iterator[LabServer]:
    """The drone lab as `ros2 launch flightcontroller fly.launch` starts it (keyboard in adopt mode)."""
    server = LabServer(["--launch", "fly"], tmp_path / "server.log")
    try:
        server.wait_ready()
        yield server
    finally:
        server.stop()


def test_publisher_panel_position_at_1hz_flies_drone_to_5_5_10(
    page: Page, fly_server: LabServer, screenshot_dir: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    open_lab_page(page, fly_server)
    page.get_by_role("button", name="Quadrotor", exact=True).click()
    wait_until(
        lambda: math.dist(position(fly_server), HOME_M) < 0.15, "the drone hovering at (0, 0, 3)", HOME_WAIT_S
    )
    wait_stopped(fly_server)
    wait_frames(page)
    png = save_screenshot(page, screenshot_dir, "drone_hovering.png", capsys)
    hovering = find_drone(CanvasShot.of(page, png))
    assert_drone_seen(hovering, "drone_hovering.png")

    page.get_by_text("Message Publisher", exact=True).click()
    assert page.get_by_label("Topic", exact=True).input_value() == "/uav/input/position"  # preselected
    assert page.get_by_label("Type", exact=True).input_value() == "geometry_msgs/msg/Vector3"
    for field, value in (("x", "5"), ("y", "5"), ("z", "10"), ("Rate (Hz)", "1")):
        page.get_by_label(field, exact=True).fill(value)
    page.get_by_label("Enabled", exact=True).check()
    page.wait_for_function("() => document.body.innerText.includes('publishing on')")

    publishers = httpx.get(f"{fly_server.url}/api/publishers", timeout=5.0).json()
    assert [(p["topic"], p["rate_hz"], p["msg"]) for p in publishers] == [
        ("/uav/input/position", 1.0, {"x": 5.0, "y": 5.0, "z": 10.0})
    ]
    wait_until(lambda: math.dist(position(fly_server), (5.0, 5.0, 10.0)) < ARRIVED_M, "the drone at (5, 5, 10)",
               FLIGHT_WAIT_S)  # fmt: skip
    wait_stopped(fly_server)
    assert math.dist(position(fly_server), (5.0, 5.0, 10.0)) < ARRIVED_M
    assert httpx.get(f"{fly_server.url}/api/publishers", timeout=5.0).json()[0]["count"] >= 2  # it repeats

    wait_frames(page)
    png = save_screenshot(page, screenshot_dir, "drone_at_5_5_10.png", capsys)
    there = find_drone(CanvasShot.of(page, png))
    assert_drone_seen(there, "drone_at_5_5_10.png")
    # The default camera looks from -y: +x is to the right, and higher (and farther) is up the image.
    assert there.centre[0] > hovering.centre[0] + MOVED_PX, (hovering, there)
    assert there.centre[1] < hovering.centre[1] - MOVED_PX, (hovering, there)
