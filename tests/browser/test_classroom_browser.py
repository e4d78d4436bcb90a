"""A class server (``--classroom``) in a real headless Chromium: two students, two browser
contexts, each joined through the page's form. Each student's keys fly only their own drone and
abort only their own rocket; the other world is checked through the REST API with its token."""

from __future__ import annotations

import io
import math
import re
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from labpage import (
    LOAD_WAIT_MS,
    lab_page,
    open_lab_page,
    save_screenshot,
    still,
    wait_until,
)
from labserver import LabServer
from PIL import Image
from playwright.sync_api import Browser, Page
from shots import blobs, hub_green
from support.http import HTTP

from server.base.loop_priority import scheduling_of

# Ada's drone must hover where it stopped (still is judged on the sim's clock, labpage.still) while
# two pages draw beside it. A world starved of CPU flies slower than real time rather than on stale
# commands (tests/quadrotor/test_late_ticks.py), so this runs in the browser part with the others.
pytestmark = pytest.mark.browser

CODE = "TEST42"
HOME_M = (0.0, 0.0, 3.0)  # the drone keyboard manager's start setpoint
# Each position read took about 4 s here while two worlds and two software-WebGL pages shared 2 cores.
HOME_WAIT_S = 90.0
PRESSES = 2  # a metre each
MOVED_M = 0.5  # far more than hover jitter
STILL_M = 0.15
SMALL = {"width": 800, "height": 600}
VIEW_WAIT_S = 60.0
HTTP_WAIT_S = 30.0  # a class server with two whole worlds and two pages in software WebGL, on 2 cores
MIN_DRONE_PX = 6  # a drone 60 m from the camera is a few pixels across
MIN_APART_PX = 20  # two arenas apart


@pytest.fixture(scope="module")
def class_server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[LabServer]:
    """A class server with the whole lab per world, as a class gets it (the drone's keyboard
    manager in its default mode: a metre per press), the rocket waiting."""
    server = LabServer(
        ["--classroom", "--class-code", CODE, "--launch", "all", "start_delay:=3600"],
        tmp_path_factory.mktemp("classroom") / "server.log",
    )
    try:
        server.wait_ready()
        yield server
    finally:
        server.stop()


class Student:
    """One student's browser context, page and token (read from the page's HTTP-only cookie)."""

    def __init__(self, page: Page, server: LabServer, name: str, code: str = CODE) -> None:
        """Join through the page's form; the lab page then loads (``ready`` waits for it)."""
        self.page, self.server = page, server
        page.goto(server.url + "/", timeout=LOAD_WAIT_MS)
        page.fill("#name", name)
        page.fill("#code", code)
        with page.expect_navigation(timeout=LOAD_WAIT_MS):  # the form reloads the page once the world is up
            page.click("#go")

    def ready(self) -> Student:
        self.page.wait_for_load_state("domcontentloaded", timeout=LOAD_WAIT_MS)
        # The form reloaded the page into the student's own world. Presses need no steady frame
        # rate (each moves the setpoint a metre), and two pages drawing at once rarely hold one.
        open_lab_page(self.page, None, settle_ms=0)
        cookies = {c["name"]: c["value"] for c in self.page.context.cookies()}
        self.token = cookies["lab_token"]
        me = HTTP.get(f"{self.server.url}/api/classroom/me", headers=self.auth, timeout=HTTP_WAIT_S)
        self.world = me.json()["world"]
        return self

    @property
    def auth(self) -> dict[str, str]:
        return {"Authorization": f"Bearer {self.token}"}

    def topic(self, name: str) -> dict[str, Any]:
        reply = HTTP.get(
            f"{self.server.url}/api/topics/{name.lstrip('/')}", headers=self.auth, timeout=HTTP_WAIT_S
        )
        reply.raise_for_status()
        return reply.json()

    def position(self) -> tuple[float, float, float]:
        p = self.topic("/uav/sensors/gps")["latest"]["pose"]["position"]
        return p["x"], p["y"], p["z"]

    def still(self) -> tuple[float, float, float] | None:
        """Where the drone is if it is still (labpage.still: judged on the sim's clock); else None."""
        return still(self.topic)

    def setpoint(self) -> tuple[float, float, float] | None:
        """Where the student's keyboard manager last told the drone to go (None before it has)."""
        v = self.topic("/uav/input/position")["latest"]
        return None if v is None else (v["x"], v["y"], v["z"])

    def aborted(self) -> bool:
        return bool((self.topic("/abort_takeoff")["latest"] or {}).get("data"))


@pytest.fixture(scope="module")
def students(chromium: Browser, class_server: LabServer) -> Iterator[tuple[Student, Student]]:
    # A small window: software WebGL loads and draws it faster, and two pages share the machine.
    with lab_page(chromium, SMALL) as ada_page, lab_page(chromium, SMALL) as bob_page:
        # Both join first, so the two pages load at the same time.
        joined = Student(ada_page, class_server, "Ada"), Student(bob_page, class_server, "Bob")
        ada, bob = (student.ready() for student in joined)
        for s in (ada, bob):
            wait_until(
                lambda s=s: math.dist(s.position(), HOME_M) < STILL_M,
                f"{s.world}'s drone at home",
                HOME_WAIT_S,
            )
        yield ada, bob


def test_two_students_have_two_worlds(students: tuple[Student, Student]) -> None:
    ada, bob = students
    assert (ada.world, bob.world) == ("ada", "bob")
    other = HTTP.get(
        f"{ada.server.url}/api/topics", headers={**ada.auth, "X-Lab-World": "bob"}, timeout=HTTP_WAIT_S
    )
    assert other.status_code == 403


def press(student: Student, key: str, sign: int) -> None:
    """``PRESSES`` presses of ``key``, each once the setpoint has taken the one before: the
    manager's /keydown subscription keeps one message (depth 1, as the handout's), so two presses
    that reach it before its world's loop has taken the first (on a loaded machine) make one step."""
    for done in range(1, PRESSES + 1):
        student.page.keyboard.press(key)
        goal = HOME_M[0] + sign * done
        wait_until(
            lambda goal=goal: (at := student.setpoint()) is not None and abs(at[0] - goal) < 1e-6,
            f"{student.world}'s setpoint {done} m along x",
        )


def test_arrow_keys_fly_only_the_students_own_drone(students: tuple[Student, Student]) -> None:
    ada, bob = students
    ada_before, bob_before = ada.position(), bob.position()
    press(bob, "ArrowRight", +1)
    wait_until(lambda: bob.position()[0] - bob_before[0] > MOVED_M, "bob's drone to move right")
    assert math.dist(ada.position(), ada_before) < STILL_M  # Ada's drone did not take Bob's keys
    press(ada, "ArrowLeft", -1)
    wait_until(lambda: ada_before[0] - ada.position()[0] > MOVED_M, "ada's drone to move left")
    assert bob.position()[0] - bob_before[0] > MOVED_M  # Bob's is still to the right, not back left


def test_a_aborts_only_the_students_own_rocket(students: tuple[Student, Student]) -> None:
    ada, bob = students
    assert not ada.aborted() and not bob.aborted()
    ada.page.keyboard.press("a")
    wait_until(ada.aborted, "ada's /abort_takeoff true")
    assert ada.topic("/keydown")["publish_count"] >= 1
    assert not bob.aborted()
    assert all(k["latest"] is None or k["latest"]["code"] != 97 for k in [bob.topic("/keydown")])


def two_drones_drawn(page: Page) -> list[list[tuple[int, int]]] | None:
    """The class view's green drone blobs, once there are at least two far enough apart."""
    png = page.locator("#view").screenshot()
    rgb = np.asarray(Image.open(io.BytesIO(png)).convert("RGB")).astype(np.int16)
    found = [b for b in blobs(hub_green(rgb[..., 0], rgb[..., 1], rgb[..., 2])) if len(b) >= MIN_DRONE_PX]
    if len(found) < 2:
        return None
    centres = [np.mean(np.array(b), axis=0) for b in found]
    apart = max(math.dist(a, b) for a in centres for b in centres)
    return found if apart >= MIN_APART_PX else None


def test_the_instructors_page_resets_one_world_and_the_other_keeps_its_state(
    chromium: Browser,
    class_server: LabServer,
    students: tuple[Student, Student],
    screenshot_dir: Path,
    capsys: pytest.CaptureFixture[str],
) -> None:
    ada, bob = students
    found = re.search(r"/instructor\?token=(\S+)", class_server.log_tail(10**6))
    assert found is not None, "the class server prints the instructor's link once"
    wait_until(lambda: abs(bob.position()[0]) > MOVED_M, "bob's drone away from the origin (the keys test)")
    # The keys test's presses: Ada's setpoint a metre left of home for each (a reset would show).
    ada_goal = (HOME_M[0] - PRESSES, HOME_M[1], HOME_M[2])
    wait_until(
        lambda: (at := ada.setpoint()) is not None and math.dist(at, ada_goal) < 1e-6,
        "ada's setpoint after her presses",
    )
    with lab_page(chromium, SMALL) as page:
        page.goto(f"{class_server.url}/instructor?token={found.group(1)}", timeout=LOAD_WAIT_MS)
        page.wait_for_selector("tr[data-world='bob']")
        assert page.url == f"{class_server.url}/instructor"  # the token left the address bar
        rows = page.inner_text("#worlds")
        assert "Ada" in rows and "Bob" in rows
        # The load panel: a verdict and this server's two worlds with its CPU and memory.
        page.wait_for_function(
            "() => /2\\/\\d+ worlds, CPU/.test(document.getElementById('load-places').textContent)"
        )
        assert page.inner_text("#load-verdict") in ("ok", "near", "full")
        assert "MiB" in page.inner_text("#load-places")
        # and its worlds' loop's scheduling class, as the kernel has it (real-time, run as root)
        assert scheduling_of(class_server.proc.pid) == "realtime"
        assert "real-time loop" in page.inner_text("#load-places")
        # and the machine's world budget, which both worlds count against (--worlds-per-core)
        assert re.search(
            r"the machine: 2 of its budget of \d+ worlds \(\d+ cores\)", page.inner_text("#load-places")
        )
        # The 3D view: both worlds listed, and two drones drawn apart (an arena each).
        view = page.frame_locator("#view")
        view.get_by_text("2 worlds").wait_for(timeout=LOAD_WAIT_MS)
        listed = view.locator("body").inner_text()
        assert "Ada (ada)" in listed and "Bob (bob)" in listed, listed[-500:]
        drones = wait_until(lambda: two_drones_drawn(page), "two drones drawn in the class view", VIEW_WAIT_S)
        sizes = sorted(len(blob) for blob in drones)
        assert sizes[-2] >= MIN_DRONE_PX, sizes
        save_screenshot(page, screenshot_dir, "instructor_class_view.png", capsys)
        page.click("tr[data-world='bob'] button:text-is('Reset')")
        page.wait_for_function("() => document.getElementById('status').textContent === 'reset bob'")
    wait_until(lambda: abs(bob.position()[0]) < STILL_M, "bob's drone back at the origin after the reset")
    # Ada's world kept its state: her setpoint as it was, and her drone stopped there, not at home.
    # (Her drone may still have been settling when Bob's was reset: judged once it is still.)
    assert (kept := ada.setpoint()) is not None and math.dist(kept, ada_goal) < 1e-6
    wait_until(
        lambda: (p := ada.still()) is not None and math.dist(p, ada_goal) < STILL_M,
        "ada's drone still at her setpoint",
        HOME_WAIT_S,
    )
    assert ada.aborted()  # and her rocket is still aborted: her world kept its state
