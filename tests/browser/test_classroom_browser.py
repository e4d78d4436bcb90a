"""A class server (``--classroom``) in a real headless Chromium: two students, two browser
contexts, each joined through the page's form. Each student's keys fly only their own drone and
abort only their own rocket; the other world is checked through the REST API with its token."""

from __future__ import annotations

import math
import re
import time
from collections.abc import Iterator
from typing import Any

import httpx
import pytest
from labpage import STILL_DRIFT_M, STILL_WINDOW_S, lab_page, open_lab_page, wait_until
from labserver import LabServer
from playwright.sync_api import Browser, Page

pytestmark = pytest.mark.browser

CODE = "TEST42"
HOME_M = (0.0, 0.0, 3.0)  # the drone keyboard manager's start setpoint
HOME_WAIT_S = 25.0
PRESSES = 2  # a metre each
MOVED_M = 0.5  # far more than hover jitter
STILL_M = 0.15
SMALL = {"width": 800, "height": 600}


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
        page.goto(server.url + "/")
        page.fill("#name", name)
        page.fill("#code", code)
        with page.expect_navigation():  # the form reloads the page once the world is up
            page.click("#go")

    def ready(self) -> Student:
        self.page.wait_for_load_state("domcontentloaded")
        # The form reloaded the page into the student's own world. Presses need no steady frame
        # rate (each moves the setpoint a metre), and two pages drawing at once rarely hold one.
        open_lab_page(self.page, None, settle_ms=0)
        cookies = {c["name"]: c["value"] for c in self.page.context.cookies()}
        self.token = cookies["lab_token"]
        me = httpx.get(f"{self.server.url}/api/classroom/me", headers=self.auth, timeout=5.0)
        self.world = me.json()["world"]
        return self

    @property
    def auth(self) -> dict[str, str]:
        return {"Authorization": f"Bearer {self.token}"}

    def topic(self, name: str) -> dict[str, Any]:
        reply = httpx.get(f"{self.server.url}/api/topics/{name.lstrip('/')}", headers=self.auth, timeout=5.0)
        reply.raise_for_status()
        return reply.json()

    def position(self) -> tuple[float, float, float]:
        p = self.topic("/uav/sensors/gps")["latest"]["pose"]["position"]
        return p["x"], p["y"], p["z"]

    def still(self) -> tuple[float, float, float] | None:
        """Where the drone is, if it moved under 5 cm in half a second; else None."""
        before = self.position()
        time.sleep(STILL_WINDOW_S)
        after = self.position()
        return after if math.dist(before, after) < STILL_DRIFT_M else None

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
    other = httpx.get(f"{ada.server.url}/api/topics", headers={**ada.auth, "X-Lab-World": "bob"}, timeout=5.0)
    assert other.status_code == 403


def test_arrow_keys_fly_only_the_students_own_drone(students: tuple[Student, Student]) -> None:
    ada, bob = students
    ada_before, bob_before = ada.position(), bob.position()
    for _ in range(PRESSES):
        bob.page.keyboard.press("ArrowRight")
    wait_until(lambda: bob.position()[0] - bob_before[0] > MOVED_M, "bob's drone to move right")
    assert math.dist(ada.position(), ada_before) < STILL_M  # Ada's drone did not take Bob's keys
    for _ in range(PRESSES):
        ada.page.keyboard.press("ArrowLeft")
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


def test_the_instructors_page_resets_one_world_and_the_other_keeps_its_state(
    chromium: Browser, class_server: LabServer, students: tuple[Student, Student]
) -> None:
    ada, bob = students
    found = re.search(r"/instructor\?token=(\S+)", class_server.log_tail(10**6))
    assert found is not None, "the class server prints the instructor's link once"
    wait_until(lambda: abs(bob.position()[0]) > MOVED_M, "bob's drone away from the origin (the keys test)")
    ada_before = wait_until(ada.still, "ada's drone to stop after the keys test")
    with lab_page(chromium, SMALL) as page:
        page.goto(f"{class_server.url}/instructor?token={found.group(1)}")
        page.wait_for_selector("tr[data-world='bob']")
        assert page.url == f"{class_server.url}/instructor"  # the token left the address bar
        rows = page.inner_text("#worlds")
        assert "Ada" in rows and "Bob" in rows
        page.click("tr[data-world='bob'] button:text-is('Reset')")
        page.wait_for_function("() => document.getElementById('status').textContent === 'reset bob'")
    wait_until(lambda: abs(bob.position()[0]) < STILL_M, "bob's drone back at the origin after the reset")
    assert math.dist(ada.position(), ada_before) < STILL_M  # Ada's drone hovers where it was
    assert ada.aborted()  # and her rocket is still aborted: her world kept its state
