"""The instructor's checkpoint table in a real headless Chromium, against a class server
(``python -m server --classroom --launch fly``): Ada and Bob join through REST; Ada has begun
checkpoint 2 (her positions at 1 Hz), Bob has not. The table shows each where they are, a cell
opens that student's evidence and report, the class's answers show side by side, the CSV and the
reports' zip download, and a report checked on the page is named valid, an edited one edited.

No drone is flown to the end here: two whole worlds on a loaded 2-core machine do not keep real
time (test_guide_browser.py ticks checkpoint 2 in a lab of its own; tests/checkpoints the class's
done cells on a stepped clock). So the evidence of a done checkpoint 2 is served in place of
Ada's where the page asks for it, and the page draws it: the flight's picture as the report makes
it, the timeline in the instructor's local time. Every wait is bounded.
"""

from __future__ import annotations

import csv
import re
import zipfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from labpage import LOAD_WAIT_MS, lab_page, wait_until
from labserver import LabServer
from playwright.sync_api import Browser, Page
from support.http import HTTP

pytestmark = pytest.mark.browser

CODE = "GUIDE7"
HTTP_WAIT_S = 30.0  # a class server with two whole worlds, on 2 cores
ADA_ANSWER = "Ada: the keys, as keyboard_msgs/msg/Key"
BOB_ANSWER = "Bob: /keydown and /keyup"
FILE = {"content-type": "application/octet-stream"}
Auth = dict[str, str]


@pytest.fixture(scope="module")
def class_server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[LabServer]:
    """A class server with the drone lab per world."""
    server = LabServer(
        ["--classroom", "--class-code", CODE, "--launch", "fly"],
        tmp_path_factory.mktemp("class") / "server.log",
    )
    try:
        server.wait_ready()
        yield server
    finally:
        server.stop()


def bearer(token: str) -> Auth:
    return {"Authorization": f"Bearer {token}"}


def join(server: LabServer, name: str) -> Auth:
    """A student joined through REST; their bearer header."""
    reply = HTTP.post(
        f"{server.url}/api/classroom/join", json={"name": name, "code": CODE}, timeout=HTTP_WAIT_S
    )
    reply.raise_for_status()
    return bearer(reply.json()["token"])


def call(server: LabServer, method: str, path: str, auth: Auth, **kwargs: Any) -> Any:
    reply = HTTP.request(method, f"{server.url}{path}", headers=auth, timeout=HTTP_WAIT_S, **kwargs)
    reply.raise_for_status()
    return reply


def fly_state(server: LabServer, auth: Auth) -> str:
    data = call(server, "GET", "/api/checkpoints", auth).json()
    return next(c["state"] for c in data["checkpoints"] if c["name"] == "fly_to_point")


@pytest.fixture(scope="module")
def class_with_two(class_server: LabServer) -> tuple[Auth, Auth, Auth]:
    """Ada under way with checkpoint 2, Bob not begun; each answered q1. The instructor's, Ada's
    and Bob's headers."""
    ada, bob = join(class_server, "Ada"), join(class_server, "Bob")
    call(class_server, "PUT", "/api/checkpoints/answers/q1", ada, json={"text": ADA_ANSWER})
    call(class_server, "PUT", "/api/checkpoints/answers/q1", bob, json={"text": BOB_ANSWER})
    body = {"topic": "/uav/input/position", "msg": {"x": 5, "y": 5, "z": 10}, "rate_hz": 1}
    call(class_server, "POST", "/api/publishers", ada, json=body)
    wait_until(
        lambda: fly_state(class_server, ada) != "not_started", "Ada's checkpoint 2 under way", HTTP_WAIT_S
    )
    found = re.search(r"/instructor\?token=(\S+)", class_server.log_tail(10**6))
    assert found is not None, "the class server prints the instructor's link once"
    return bearer(found.group(1)), ada, bob


def download(page: Page, selector: str, folder: Path) -> Path:
    with page.expect_download() as started:
        page.locator(selector).click()
    path = folder / started.value.suggested_filename
    started.value.save_as(path)
    return path


def test_instructor_table_shows_each_student_where_they_are_with_evidence_answers_and_exports(
    chromium: Browser, class_server: LabServer, class_with_two: tuple[Auth, Auth, Auth], tmp_path: Path
) -> None:
    instructor, ada, bob = class_with_two
    ada_state, bob_state = fly_state(class_server, ada), fly_state(class_server, bob)
    assert (ada_state, bob_state) in {("in_progress", "not_started"), ("done", "not_started")}
    token = instructor["Authorization"].removeprefix("Bearer ")
    with lab_page(chromium) as page:
        page.goto(f"{class_server.url}/instructor?token={token}", timeout=LOAD_WAIT_MS)
        page.wait_for_function(
            "() => document.querySelectorAll('#checkpoints-rows tr').length === 2", timeout=LOAD_WAIT_MS
        )
        # a row's name: the student's as joined, or their world's (either case)
        cell = "#checkpoints-rows tr[data-student='{}' i] button[data-checkpoint='{}']"
        ada_cell = page.locator(cell.format("Ada", "fly_to_point")).get_attribute("class")
        assert ada_cell in {f"cell {ada_state}", "cell done"}, ada_cell  # she may have arrived since
        assert page.locator(cell.format("Bob", "fly_to_point")).get_attribute("class") == "cell not_started"
        assert page.locator("#checkpoints-head th").all_inner_texts() == [
            "Student",
            "keyboard_abort",
            "fly_to_point",
            "launch_and_keys",
        ]

        page.locator(cell.format("Ada", "fly_to_point")).click()  # what the server has of it
        page.locator("#evidence-body h3").filter(has_text=re.compile("ada", re.IGNORECASE)).wait_for()
        # the progress line: her positions so far, or, if she has arrived since, the hold that ended it
        progress = page.locator("#evidence-body p.muted").first.inner_text()
        assert "positions" in progress or progress.startswith("done: the drone held (5, 5, 10)"), progress
        href = page.locator("#evidence-body a").get_attribute("href") or ""
        assert href.startswith("/api/checkpoints/report?format=html&world="), href
        shown = call(class_server, "GET", href, instructor)
        assert "checkpoints of ada" in shown.text.lower()
        page.locator("#evidence-close").click()

        page.select_option("#question", "q1")  # the class's answers side by side
        cards = page.locator("#answers article").all()
        assert sorted((c.locator("h4").inner_text().lower(), c.locator("p").inner_text()) for c in cards) == [
            ("ada", ADA_ANSWER),
            ("bob", BOB_ANSWER),
        ]

        with download(page, "#checkpoints-csv", tmp_path).open(newline="") as table:
            rows = {row["student"].lower(): row for row in csv.DictReader(table)}
        assert (rows["ada"]["q1"], rows["bob"]["q1"]) == (ADA_ANSWER, BOB_ANSWER)
        assert rows["ada"]["fly_to_point state"] in {"in_progress", "done"}
        assert rows["bob"]["fly_to_point state"] == "not_started"
        with zipfile.ZipFile(download(page, "#checkpoints-zip", tmp_path)) as archive:
            assert len([n for n in archive.namelist() if n.endswith(".json")]) == 2

        report = call(class_server, "GET", "/api/checkpoints/report?format=json", ada).content
        at = report.index(b"keyboard_msgs")  # in Ada's answer: still a report, no longer the one signed
        (tmp_path / "ada.json").write_bytes(report)
        (tmp_path / "ada-edited.json").write_bytes(report[:at] + b"K" + report[at + 1 :])
        result = page.locator("#verify-result")
        page.set_input_files("#verify-file", str(tmp_path / "ada.json"))
        page.wait_for_function("() => /: valid/.test(document.getElementById('verify-result').textContent)")
        assert result.get_attribute("class") == "good"
        assert "(student: ada)" in result.inner_text().lower()
        page.set_input_files("#verify-file", str(tmp_path / "ada-edited.json"))
        page.wait_for_function("() => /: edited/.test(document.getElementById('verify-result').textContent)")
        assert result.get_attribute("class") == "bad"


# A done checkpoint 2 as the server records it (the lab's clock reads as Unix time), served in
# place of Ada's, whose drone is not flown to the end here (see the module's note).
FLOWN_AT_S = 1_795_000_000.0  # 2026-11-18, in the afternoon (UTC)
TRACK = [[FLOWN_AT_S + t, 0.05 * t, 0.05 * t, 3 + 0.07 * t] for t in range(0, 100, 2)]
EVIDENCE = {
    "target": [5.0, 5.0, 10.0],
    "publisher": "/position_publisher",
    "rate_hz": 1.0,
    "held_s": 3.02,
    "setpoints": [
        {
            "t_s": FLOWN_AT_S + t,
            "what": "/uav/input/position",
            "value": [5.0, 5.0, 10.0],
            "by": "/position_publisher",
        }
        for t in range(0, 100, 10)
    ],
    "track": TRACK,
}


def test_instructor_evidence_shows_the_flights_picture_and_its_timeline_in_local_time(
    chromium: Browser, class_server: LabServer, class_with_two: tuple[Auth, Auth, Auth]
) -> None:
    from server.world.checkpoints.plot import svg_data_url, track_svg

    instructor, _ada, _bob = class_with_two
    token = instructor["Authorization"].removeprefix("Bearer ")
    drawn = svg_data_url(track_svg(TRACK, EVIDENCE["target"], "fly_to_point: the drone's track"))

    def done_checkpoints(route: Any) -> None:
        body = route.fetch().json()
        for c in body["checkpoints"]:
            if c["name"] == "fly_to_point":
                c.update(state="done", done_at="2026-11-18T15:33:20+00:00", evidence=EVIDENCE)
        route.fulfill(json=body)

    def report_with_picture(route: Any) -> None:
        body = route.fetch().json()
        for c in body["checkpoints"]:
            if c["name"] == "fly_to_point":
                c["picture"] = drawn
        route.fulfill(json=body)

    with lab_page(chromium) as page:
        page.route(re.compile(r"/api/checkpoints\?world="), done_checkpoints)
        page.route(re.compile(r"/api/checkpoints/report\?format=json&world="), report_with_picture)
        page.goto(f"{class_server.url}/instructor?token={token}", timeout=LOAD_WAIT_MS)
        page.wait_for_function(
            "() => document.querySelectorAll('#checkpoints-rows tr').length === 2", timeout=LOAD_WAIT_MS
        )
        page.locator(
            "#checkpoints-rows tr[data-student='Ada' i] button[data-checkpoint='fly_to_point']"
        ).click()
        body = page.locator("#evidence-body")
        body.locator("img").wait_for(timeout=LOAD_WAIT_MS)
        assert body.locator("img").first.get_attribute("src") == drawn  # the flight, drawn
        assert body.locator("img").first.evaluate("img => img.complete && img.naturalWidth > 0")
        local = page.evaluate(f"() => new Date({FLOWN_AT_S} * 1000).toLocaleTimeString()")
        cells = body.locator("section.timeline td").all_inner_texts()
        assert cells[:4] == [local, "/uav/input/position", "[5,5,10]", "/position_publisher"], cells
        visible = body.evaluate(
            "b => [...b.childNodes].filter(n => n.nodeName !== 'DETAILS').map(n => n.textContent).join(' ')"
        )
        assert str(int(FLOWN_AT_S)) not in visible  # no epoch seconds outside the folded JSON
        assert "held_s" in body.locator("table.facts").inner_text()
        box = page.locator("#evidence").bounding_box()
        assert box is not None and box["x"] >= 0 and box["x"] + box["width"] <= page.viewport_size["width"]
