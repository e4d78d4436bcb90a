"""The lab page's guide in a real headless Chromium, against one ``python -m server --launch
fly`` for the module (the instructor's table: test_instructor_checkpoints_browser.py):

- an answer typed in the guide is saved (the page says so, the server has it), and its keys reach
  neither the keyboard node nor viser's camera, while a key on the 3D view still reaches the
  keyboard node; an answer over the size limit is not saved and the page says why;
- the guide ticks checkpoint 2 while the student flies with the Message Publisher panel (positions
  at 1 Hz to (5, 5, 10)), and the page sends the server a picture of its 3D view that shows the
  drone;
  the report downloads from the guide (JSON and HTML), its signature verifies (the verify route,
  and ``ros2lab report verify FILE``), and a changed byte fails verification.

Every wait is bounded: Playwright's own timeouts, or a polled deadline.
"""

from __future__ import annotations

import base64
import io
import json
import math
import os
import subprocess
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from labpage import lab_page, open_lab_page, wait_until
from labserver import LabServer
from PIL import Image
from playwright.sync_api import Browser, Page, Request
from shots import CanvasShot, assert_drone_seen, find_drone
from support.forked_cli import cli_command
from support.http import HTTP

pytestmark = pytest.mark.browser

VIEWPORT = {"width": 1366, "height": 768}  # wide enough that the guide opens unfolded
TARGET_M = (5.0, 5.0, 10.0)
ARRIVED_M = 0.3  # checkpoint 2's own bound
FLIGHT_WAIT_S = 90.0  # the flight (about 10 s), five messages at 1 Hz and 3 s at the point, on a busy machine
DONE_WAIT_MS = 90_000
HTTP_WAIT_S = 30.0  # a page drawing in software WebGL beside the server, on 2 cores
ANSWER = "It publishes /keydown and /keyup as keyboard_msgs/msg/Key, one message per key event."
LIMIT_BYTES = 8 * 1024
FILE = {"content-type": "application/octet-stream"}  # a report file as it is
CLI_WAIT_S = 60.0
Auth = dict[str, str]


@pytest.fixture(scope="module")
def fly_server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[LabServer]:
    """The drone lab as `ros2 launch flightcontroller fly.launch` starts it."""
    server = LabServer(["--launch", "fly"], tmp_path_factory.mktemp("guide") / "server.log")
    try:
        server.wait_ready()
        yield server
    finally:
        server.stop()


@pytest.fixture(scope="module")
def lab(chromium: Browser, fly_server: LabServer) -> Iterator[tuple[Page, Auth]]:
    """One lab page for the module (loading one costs 10-30 s here), its guide shown; and the
    headers a request needs (none: a lab on loopback)."""
    with lab_page(chromium, VIEWPORT) as page:
        open_lab_page(page, fly_server)
        page.wait_for_selector("#teleop-guide li.checkpoint[data-name='fly_to_point']")
        yield page, {}


def get(server: LabServer, path: str, auth: Auth) -> Any:
    reply = HTTP.get(f"{server.url}{path}", headers=auth, timeout=HTTP_WAIT_S)
    reply.raise_for_status()
    return reply.json()


def checkpoint(server: LabServer, auth: Auth, name: str) -> dict[str, Any]:
    return next(c for c in get(server, "/api/checkpoints", auth)["checkpoints"] if c["name"] == name)


def answer_on_server(server: LabServer, auth: Auth, question: str) -> str:
    return next(
        q["answer"] for q in get(server, "/api/checkpoints", auth)["questions"] if q["id"] == question
    )


def key_events(server: LabServer, auth: Auth) -> int:
    """Messages the keyboard node has published on /keydown (none yet: 0)."""
    reply = HTTP.get(f"{server.url}/api/topics/keydown", headers=auth, timeout=HTTP_WAIT_S)
    return reply.json()["publish_count"] if reply.status_code == 200 else 0


def position(server: LabServer, auth: Auth) -> tuple[float, float, float]:
    p = get(server, "/api/topics/uav/sensors/gps", auth)["latest"]["pose"]["position"]
    return p["x"], p["y"], p["z"]


def verify(server: LabServer, content: bytes, auth: Auth) -> dict[str, Any]:
    reply = HTTP.post(
        f"{server.url}/api/checkpoints/verify", content=content, headers={**FILE, **auth}, timeout=HTTP_WAIT_S
    )
    reply.raise_for_status()
    return reply.json()


def edited(report: bytes) -> bytes:
    """One byte of a checkpoint's state changed: still a report, no longer the one signed."""
    at = report.index(b'"done"') + 2
    return report[:at] + b"u" + report[at + 1 :]


# -- the guide -----------------------------------------------------------------------------------
def test_guide_answer_is_saved_and_its_keys_stay_in_the_box(
    lab: tuple[Page, Auth], fly_server: LabServer
) -> None:
    page, auth = lab
    box = page.locator("#guide-answer-q1")
    before = key_events(fly_server, auth)
    page.locator("#teleop-hud").get_by_role(
        "button", name="arena", exact=True
    ).click()  # a camera that holds still
    camera = "JSON.stringify(window.__viserMutable.camera.position.toArray())"
    # The switch to the arena view moves the camera over a few frames: read it once it has held
    # still for ten frames in a row (at most 600 frames), not while it is still on its way.
    camera_before = page.evaluate(
        """async () => {
            const read = () => JSON.stringify(window.__viserMutable.camera.position.toArray());
            let last = read();
            for (let still = 0, frames = 0; still < 10; frames++) {
                if (frames > 600) return null;
                await new Promise((done) => requestAnimationFrame(done));
                const now = read();
                still = now === last ? still + 1 : 0;
                last = now;
            }
            return last;
        }"""
    )
    assert camera_before is not None, "the camera never held still after the switch to the arena view"
    box.click()
    box.press_sequentially(ANSWER[:10])  # typed key by key: "It publish" has an "s" and an "a"
    box.press("ArrowRight")
    box.fill(ANSWER)  # the rest at once
    status = page.locator(".guide-question[data-question='q1'] .saved")
    status.filter(has_text="saved at").wait_for()
    assert answer_on_server(fly_server, auth, "q1") == ANSWER
    assert page.locator(".guide-question[data-question='q1'] .size").inner_text() == (
        f"{len(ANSWER)} / {LIMIT_BYTES:,} bytes"
    )
    assert key_events(fly_server, auth) == before, "keys typed in the answer box reached the keyboard node"
    assert page.evaluate(camera) == camera_before, "keys typed in the answer box moved viser's camera"

    box.fill("x" * (LIMIT_BYTES + 1))
    status.filter(has_text="too long to save").wait_for()
    assert page.locator(".guide-question[data-question='q1'] .size.over").count() == 1
    box.fill(ANSWER)  # back as saved: nothing to send
    status.filter(has_text="saved at").wait_for()
    assert answer_on_server(fly_server, auth, "q1") == ANSWER

    page.mouse.click(VIEWPORT["width"] / 2, VIEWPORT["height"] / 2)  # the 3D view has the keyboard again
    page.keyboard.press("a")
    wait_until(lambda: key_events(fly_server, auth) > before, "a key on the 3D view reaching /keydown")


def fly_with_publisher_panel(page: Page) -> None:
    """Positions at 1 Hz to (5, 5, 10) from the Message Publisher panel, as a student fills it in
    (tests/browser/test_teleop_browser.py: each field waits for the server's preview to show it)."""
    page.get_by_text("Message Publisher", exact=True).click()
    assert page.get_by_label("Topic", exact=True).input_value() == "/uav/input/position"
    for field, value, shown in (
        ("x", "5", "x: 5.0"),
        ("y", "5", "y: 5.0"),
        ("z", "10", "z: 10.0"),
        ("Rate (Hz)", "2", "at 2 Hz"),
        ("Rate (Hz)", "1", "at 1 Hz"),
    ):
        page.get_by_label(field, exact=True).fill(value)
        page.wait_for_function("(s) => document.body.innerText.includes(s)", arg=shown)
    page.get_by_label("Enabled", exact=True).check()
    page.wait_for_function("() => document.body.innerText.includes('publishing on')")


def drone_in_png(png: bytes) -> CanvasShot:
    rgb = np.asarray(Image.open(io.BytesIO(png)).convert("RGB")).astype(np.int16)
    return CanvasShot(rgb, np.ones(rgb.shape[:2], dtype=bool))


def test_guide_ticks_checkpoint_2_as_the_publisher_panel_flies_and_its_report_verifies(
    lab: tuple[Page, Auth], fly_server: LabServer, tmp_path: Path
) -> None:
    page, auth = lab
    item = page.locator("#teleop-guide li.checkpoint[data-name='fly_to_point']")
    assert item.get_attribute("data-state") != "done"
    assert item.locator("code").count() > 0  # its steps name commands or buttons

    def is_capture(request: Request) -> bool:
        return request.method == "POST" and request.url.endswith("/api/checkpoints/fly_to_point/capture")

    with page.expect_request(is_capture, timeout=DONE_WAIT_MS) as sent:
        fly_with_publisher_panel(page)
        page.wait_for_selector(
            "#teleop-guide li.checkpoint[data-name='fly_to_point'][data-state='done']", timeout=DONE_WAIT_MS
        )
    assert math.dist(position(fly_server, auth), TARGET_M) < ARRIVED_M
    assert item.locator(".badge").inner_text().startswith("done ")
    summary = page.locator("#teleop-guide .summary").inner_text()
    assert summary.startswith("1 of 3"), summary
    assert sent.value.headers.get("content-type") == "image/png"
    assert sent.value.response() is not None  # answered
    wait_until(
        lambda: checkpoint(fly_server, auth, "fly_to_point")["has_capture"],
        "the server to keep the picture",
    )
    assert page.evaluate("window.__teleop.guide.capture.error") is None

    json_file = download(page, "#teleop-guide .report a.download-json", tmp_path)
    html_file = download(page, "#teleop-guide .report a.download-html", tmp_path)
    assert json_file.suffix == ".json" and html_file.suffix == ".html"
    report = json.loads(json_file.read_bytes())
    assert "signature" in report
    flown = next(c for c in report["checkpoints"] if c["name"] == "fly_to_point")
    assert flown["state"] == "done"
    scheme, _, data = flown["picture"].partition(",")
    assert scheme == "data:image/png;base64"  # the page's picture, not the server's plot (SVG)
    assert_drone_seen(find_drone(drone_in_png(base64.b64decode(data))), "the page's picture of checkpoint 2")
    for good in (json_file, html_file):
        verdict = verify(fly_server, good.read_bytes(), auth)
        assert verdict["valid"] is True, (good.name, verdict)
        verdict = verify(fly_server, edited(good.read_bytes()), auth)
        assert verdict["valid"] is False and verdict["reason"].startswith("edited"), (good.name, verdict)
    changed = tmp_path / "changed.json"
    changed.write_bytes(edited(json_file.read_bytes()))
    assert ros2lab_verify(fly_server, json_file).returncode == 0
    assert ros2lab_verify(fly_server, changed).returncode == 1


def ros2lab_verify(server: LabServer, report: Path) -> subprocess.CompletedProcess[str]:
    """``ros2lab report verify FILE`` as the student runs it, against the lab (no token)."""
    env = {k: v for k, v in os.environ.items() if k != "ROS2LAB_TOKEN"}
    return subprocess.run(
        cli_command("report", "verify", str(report), "--url", server.url),
        capture_output=True,
        text=True,
        timeout=CLI_WAIT_S,
        env=env,
    )


def download(page: Page, selector: str, folder: Path) -> Path:
    with page.expect_download() as started:
        page.locator(selector).click()
    path = folder / started.value.suggested_filename
    started.value.save_as(path)
    return path
