"""Keyboard teleop and the page's tools in a real headless Chromium, against ``python -m server``.

Hold mode (``--launch fly keyboard_mode:=hold``): holding → the drone moves, releasing → it
stops; and every way a hold can end without a keyup ends it on the server: a blur (the page
sends ``release_all``), a closed or crashed page (the channel closes), a frozen page (the
server's dead-man timer). The Message Publisher panel flies the drone to (5, 5, 10) at 1 Hz.
Screenshots are checked for what their names say by colour classes in the 3D canvas (shots.py).

Chromium, the server subprocess, the page and the rocket abort test live in conftest.py,
labserver.py, labpage.py and test_rocket_browser.py. Every wait is bounded: Playwright's own
timeouts, or a polled deadline. The ``time.sleep`` calls here are key-hold durations and
observation windows, not waits.
"""

from __future__ import annotations

import contextlib
import math
import os
import re
import signal
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from labpage import (
    HTTP_TIMEOUT_S,
    STILL_DRIFT_M,
    WAIT_S,
    lab_page,
    open_lab_page,
    position,
    save_screenshot,
    topic,
    wait_frames,
    wait_stopped,
    wait_until,
)
from labserver import LabServer
from playwright.sync_api import Browser, Page
from playwright.sync_api import Error as PlaywrightError
from shots import CanvasShot, assert_drone_seen, assert_rocket_on_pad, find_drone
from support.http import HTTP

from server.host.settings import LabLimits

pytestmark = pytest.mark.browser

KEY_RIGHT = 275  # keyboard_msgs/Key code (SDL) of ArrowRight
HOME_M = (0.0, 0.0, 3.0)  # the keyboard manager's start setpoint
HOLD_S = 1.0
BRIEF_HOLD_S = 0.3
SET_OFF_M = 0.1  # a brief hold goes on until the drone has moved this far: brief_hold
SET_OFF_WAIT_S = 5.0  # bounded: a hold that never moves it fails the callers' assertions
HOLD_ATTEMPTS = 3  # a hold the dead-man released (the page stalled) is tried again: see TestHoldMode
MOVED_M = 0.5  # hold speed 2 m/s for 1 s moves about 2 m; far more than hover jitter
# How far a hold may take the drone: hold speed 2 m/s (2.2 m/s seen) for as long as the server
# saw the key held, plus the stop: the brake setpoint (0.55 s of velocity ahead) and overshoot.
MAX_HOLD_SPEED_M_S = 2.5
STOP_M = 1.5
RELEASE_WAIT_S = WAIT_S  # a release reaches /keyup within 0.5 s (the dead-man); reading it may take seconds
HOME_WAIT_S = 25.0
FLIGHT_WAIT_S = 30.0
ARRIVED_M = 0.1
PAGE_WAIT_MS = 30_000
MOVED_PX = 20
# the server's dead-man: a channel silent this long with keys held has them released
DEADMAN_S = LabLimits().deadman_s
DEADMAN_LOG = "silent for over"  # api/websockets/keys.py logs this when its timer releases keys


@pytest.fixture
def page(chromium: Browser) -> Iterator[Page]:
    with lab_page(chromium) as page:
        yield page


def fly_home(server: LabServer) -> tuple[float, float, float]:
    """Publish the start setpoint (every keyboard mode but lab adopts it) and wait until it is held."""
    body = {"topic": "/uav/input/position", "msg": dict(zip("xyz", HOME_M, strict=True))}
    assert HTTP.post(f"{server.url}/api/publish", json=body, timeout=HTTP_TIMEOUT_S).status_code == 200
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


def stalled_since(server: LabServer, deadman_before: int) -> bool:
    """Whether the dead-man released a key since ``deadman_before``: the page or the server stalled
    for 0.5 s (software WebGL on a loaded machine) during a hold, which then ended early."""
    return deadman_releases(server) != deadman_before


def lost_race_to_deadman(server: LabServer, deadman_before: int, went_s: float) -> bool:
    """Whether the dead-man released the key while the page took longer to act (blur, close,
    crash) than the dead-man waits: a race the page may rightly lose on a loaded machine."""
    return stalled_since(server, deadman_before) and went_s > DEADMAN_S


def brief_hold(page: Page, server: LabServer) -> tuple[float, int, int] | None:
    """Press ArrowRight and keep it down for BRIEF_HOLD_S, and on until the drone has set off;
    where the drone started, /keyup's count and the dead-man's count before. None if the dead-man
    already released it (the page stalled): the key is then let go and the drone left to stop, for
    the caller to hold again.

    Why on until it has set off: on a loaded machine the keyboard manager can be handed the
    keydown late (its callbacks wait their turn on the world's executor), or the world can run
    slow. A hold ended then reaches the manager before the drone has moved, and the drone is
    rightly stopped where it was: the hold never happened, and how its ending stops the drone
    cannot be seen (a CI run saw a 0.32 s hold end 8 mm left of where it began). The hold is
    what the caller's test needs first, so it is held until the drone is seen under way
    (SET_OFF_WAIT_S at most)."""
    x0 = position(server)[0]
    before, deadman_before = keyup_count(server), deadman_releases(server)
    page.keyboard.down("ArrowRight")
    time.sleep(BRIEF_HOLD_S)  # the hold itself
    deadline = time.monotonic() + SET_OFF_WAIT_S
    while position(server)[0] <= x0 + SET_OFF_M and time.monotonic() < deadline:
        if stalled_since(server, deadman_before):
            break
        time.sleep(0.02)
    if stalled_since(server, deadman_before):
        page.keyboard.up("ArrowRight")
        wait_stopped(server)
        return None
    return x0, before, deadman_before


@pytest.mark.timing  # a hold's travel is timed on the wall clock; scripts/check runs it alone
@pytest.mark.usefixtures("home")
class TestHoldMode:
    """Holds in one open page, each tried up to HOLD_ATTEMPTS times.

    Why a retry, and why it cannot hide a fault: the page draws its 3D scene in software
    (SwiftShader), which stalls the page's main thread for seconds while it compiles shaders; a
    stall of over LabLimits.deadman_s (0.5 s) during a hold stops the page's heartbeats, and the
    server's dead-man then releases the key before the test's own way of ending the hold. That
    hold did not test what the test is about, so it is let go and held again. A try counts as
    stalled only when the server's log shows the dead-man released a key during it (DEADMAN_LOG,
    counted before and after), never on a guess; every try that was not stalled makes every
    assertion; a test whose every try stalled fails. The dead-man stays at the lab's own setting:
    the frozen-page test is about it, and a longer one would only make stalls rarer, not impossible.
    """

    def test_hold_arrow_right_for_1s_moves_drone_right_and_release_stops_it(
        self, hold_page: Page, hold_server: LabServer
    ) -> None:
        for _ in range(HOLD_ATTEMPTS):
            x0, y0, z0 = position(hold_server)
            before, deadman_before = keyup_count(hold_server), deadman_releases(hold_server)
            hold_page.keyboard.down("ArrowRight")
            time.sleep(HOLD_S)  # the hold itself
            x_held = position(hold_server)[0]
            stalled = stalled_since(hold_server, deadman_before)
            hold_page.keyboard.up("ArrowRight")
            if stalled:  # the hold ended before x_held was read: hold again
                wait_stopped(hold_server)
                continue
            assert x_held - x0 > MOVED_M
            wait_keyup(hold_server, before)
            x = assert_stopped_promptly(hold_server, x0)
            assert x > x_held - STILL_DRIFT_M  # it brakes ahead, it does not come back
            _, y, z = position(hold_server)
            assert abs(y - y0) < 0.3 and abs(z - z0) < 0.3  # moving along x keeps y and the height
            return
        pytest.fail(f"in each of {HOLD_ATTEMPTS} holds the page stalled and the dead-man released the key")

    def test_blur_during_hold_releases_key_from_page_and_drone_stops(
        self, hold_page: Page, hold_server: LabServer
    ) -> None:
        for _ in range(HOLD_ATTEMPTS):
            held = brief_hold(hold_page, hold_server)
            if held is None:  # released before the blur: hold again
                continue
            x0, before, deadman_before = held
            # Headless Chromium never loses focus (another page brought to front does not blur
            # this one), so the window gets the event a real focus loss fires.
            going = time.monotonic()
            hold_page.evaluate("window.dispatchEvent(new Event('blur'))")
            went_s = time.monotonic() - going
            wait_keyup(hold_server, before)
            assert hold_page.evaluate("window.__teleop.keys.held.size") == 0
            assert_stopped_promptly(hold_server, x0)
            if lost_race_to_deadman(hold_server, deadman_before, went_s):
                hold_page.keyboard.up("ArrowRight")
                continue  # the page took longer to blur than the dead-man waits: it may win the race
            assert not stalled_since(hold_server, deadman_before), "released by the dead-man, not by the page"
            hold_page.keyboard.up("ArrowRight")  # Playwright's own key state; the server ignores it
            return
        pytest.fail(f"in each of {HOLD_ATTEMPTS} holds the page stalled and the dead-man released the key")

    def test_frozen_page_during_hold_dead_man_releases_key_and_drone_stops(
        self, hold_page: Page, hold_server: LabServer
    ) -> None:
        paused: list[Any] = []
        for _ in range(HOLD_ATTEMPTS):
            held = brief_hold(hold_page, hold_server)
            if held is None:  # released before the freeze: hold again
                continue
            x0, before, deadman_before = held
            cdp = hold_page.context.new_cdp_session(hold_page)
            cdp.on("Debugger.paused", lambda event: paused.append(event))
            cdp.send("Debugger.enable")
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
            assert hold_page.evaluate("[...window.__teleop.keys.held]") == ["ArrowRight"]
            assert hold_page.evaluate("window.__teleop.keys.connected") is True
            hold_page.keyboard.up("ArrowRight")
            return
        pytest.fail(f"in each of {HOLD_ATTEMPTS} holds the page stalled and the dead-man released the key")


@pytest.mark.usefixtures("home")
class TestHoldModePageGone:
    """Pages that go during a hold; a server of their own, so the hold page above is closed and
    only the page under test draws. Each hold is tried up to HOLD_ATTEMPTS times, for the reason
    and on the terms TestHoldMode's docstring gives: a try the dead-man ended (the page stalled,
    or took longer to go than the dead-man waits) is held again, and only such a try."""

    @pytest.mark.parametrize("end", ["close", "crash"])
    def test_page_gone_during_hold_server_releases_key_and_drone_stops(
        self, chromium: Browser, hold_server: LabServer, end: str
    ) -> None:
        for _ in range(HOLD_ATTEMPTS):
            renderers_before = renderer_pids()
            with lab_page(chromium) as page:
                open_lab_page(page, hold_server)
                held = brief_hold(page, hold_server)
                if held is None:  # released before the page went: it cannot tell how its going does
                    continue
                x0, before, deadman_before = held
                going = time.monotonic()
                if end == "close":
                    page.close()  # pagehide (the page sends release_all), then the channel closes
                else:
                    with page.expect_event("crash", timeout=PAGE_WAIT_MS):
                        for pid in renderer_pids() - renderers_before:  # this page's (and maybe a spare)
                            os.kill(pid, signal.SIGKILL)  # no pagehide, no release_all: the channel drops
                went_s = time.monotonic() - going
                wait_keyup(hold_server, before)
                assert_stopped_promptly(hold_server, x0)
                if lost_race_to_deadman(hold_server, deadman_before, went_s):
                    continue  # the page took longer to go than the dead-man waits: it may win the race
                if stalled_since(hold_server, deadman_before):
                    # A killed page's heartbeats (every 200 ms, when its main thread is free) stop at
                    # once, so the channel's drop has what is left of the dead-man's 0.5 s since the
                    # last one: a drawing frame or two late, the dead-man may rightly come first. So
                    # may it for a closed page whose last heartbeat and pagehide came a frame or two
                    # late on a loaded machine, as the server's loop keeps the dead-man's time to the
                    # tick (it runs real-time). Held again; a page whose going never released the key
                    # loses every time and fails below.
                    continue
                return
        pytest.fail(
            f"in each of {HOLD_ATTEMPTS} holds the dead-man released the key before the page's going did"
        )


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
    # viser draws a markdown panel once its lazily loaded renderer arrives: wait for the status.
    with contextlib.suppress(PlaywrightError):
        page.wait_for_function("() => /Ready|Counting down/.test(document.body.innerText)")
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
    # The guide is a pane of the workbench now, no longer drawn over the scene: folded, it leaves
    # the scene the window's width, where the arena camera sees (5, 5, 10) beside viser's panel.
    if page.evaluate("!window.__teleop.guide.panel.folded"):
        page.locator("#teleop-guide button.fold").click()
    page.get_by_role("button", name="Quadrotor", exact=True).click()
    page.get_by_role("button", name="arena", exact=True).click()  # a still camera, to see it move
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
    # A browser sends viser one GUI update per 50 ms and keeps only the newest, so a form filled
    # faster than a person types loses values: each field waits for the server's preview to show it.
    # The preview's whole text is awaited: the guide beside it speaks of (5, 5, 10) at 1 Hz too.
    for field, value, shown in (
        ("x", "5", "{x: 5.0,"),
        ("y", "5", "y: 5.0,"),
        ("z", "10", "z: 10.0} at"),
        ("Rate (Hz)", "2", "z: 10.0} at 2 Hz"),
        ("Rate (Hz)", "1", "message: {x: 5.0, y: 5.0, z: 10.0} at 1 Hz"),
    ):
        page.get_by_label(field, exact=True).fill(value)
        page.wait_for_function("(s) => document.body.innerText.includes(s)", arg=shown)
    assert "message: {x: 5.0, y: 5.0, z: 10.0} at 1 Hz" in page.evaluate("document.body.innerText")
    page.get_by_label("Enabled", exact=True).check()
    page.wait_for_function("() => document.body.innerText.includes('publishing on')")

    publishers = HTTP.get(f"{fly_server.url}/api/publishers", timeout=HTTP_TIMEOUT_S).json()
    assert [(p["topic"], p["rate_hz"], p["msg"]) for p in publishers] == [
        ("/uav/input/position", 1.0, {"x": 5.0, "y": 5.0, "z": 10.0})
    ]
    wait_until(
        lambda: math.dist(position(fly_server), (5.0, 5.0, 10.0)) < ARRIVED_M,
        "the drone at (5, 5, 10)",
        FLIGHT_WAIT_S,
    )
    wait_stopped(fly_server)
    assert math.dist(position(fly_server), (5.0, 5.0, 10.0)) < ARRIVED_M
    assert (
        HTTP.get(f"{fly_server.url}/api/publishers", timeout=HTTP_TIMEOUT_S).json()[0]["count"] >= 2
    )  # it repeats

    wait_frames(page)
    png = save_screenshot(page, screenshot_dir, "drone_at_5_5_10.png", capsys)
    there = find_drone(CanvasShot.of(page, png))
    assert_drone_seen(there, "drone_at_5_5_10.png")
    # The arena camera looks from -y: +x is to the right, and higher (and farther) is up the image.
    assert there.centre[0] > hovering.centre[0] + MOVED_PX, (hovering, there)
    assert there.centre[1] < hovering.centre[1] - MOVED_PX, (hovering, there)
