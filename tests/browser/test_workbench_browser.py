"""The student's workbench in a real headless Chromium (SwiftShader), against ``python -m server
--launch all`` with the rocket's countdown an hour away (the page was once overlays stacked on a
full-screen 3D view, and with the code view open the scene was buried):

- at a laptop's 1366x768 and at 1920x1080, with the code view open, at least 40 % of a 20x12 grid
  of points over the window hits viser's 3D canvas (``elementFromPoint``: nothing lies on it
  there); the world's reset control is inside the window and is the topmost element at its centre,
  with nothing unfolded first, and a click on it resets the rocket;
- the panes (toolbar, guide, scene, code) lie inside the window and none overlaps another, and
  the HUD and viser's panel lie inside the scene's pane without overlapping;
- a REST publisher that flies the drone to (5, 5, 10) while the page shows the rocket switches
  the view to the drone, without a click: the drone's position projects inside the canvas, onto
  a point where the canvas is topmost, and a screenshot shows the drone there, kept near the
  canvas's centre by the follow camera; the still arena camera then shows it up and to the right
  of the centre, and smaller.

A screenshot of each page goes to artifacts/screenshots when a check fails (see conftest.py).
"""

from __future__ import annotations

import contextlib
import itertools
import math
from collections.abc import Iterator
from pathlib import Path

import pytest
from labpage import HTTP_TIMEOUT_S, lab_page, open_lab_page, position, wait_frames, wait_stopped, wait_until
from labserver import LabServer
from playwright.sync_api import Browser, Page
from shots import CanvasShot, assert_drone_seen, find_drone
from support.http import HTTP

pytestmark = pytest.mark.browser

SIZES = [(1366, 768), (1920, 1080)]
GRID = (20, 12)
LEAST_SCENE = 0.40
EDITOR_LOAD_MS = 60_000
HOME_M = (0.0, 0.0, 3.0)
FAR_M = (5.0, 5.0, 10.0)
ARRIVED_M = 0.3
VIEW_WAIT_MS = 5000  # the arena button's click to the page's view held still
CENTRED = 0.15  # in follow, the hub within this fraction of the canvas's size of its centre
FLIGHT_WAIT_S = 60.0
ROCKET_RESET_WAIT_MS = 30_000
# The share of grid points over the window whose topmost element is viser's 3D canvas (viser
# stacks a pointer-catching canvas of the same size over the WebGL one: either counts).
SCENE_SHARE_JS = """([cols, rows]) => {
  const root = document.getElementById('root');
  let hits = 0;
  for (let j = 0; j < rows; j++) for (let i = 0; i < cols; i++) {
    const e = document.elementFromPoint((i + 0.5) * innerWidth / cols, (j + 0.5) * innerHeight / rows);
    if (e && e.tagName === 'CANVAS' && root.contains(e)) hits++;
  }
  return hits / (cols * rows);
}"""
# The control's box, and whether the topmost element at its centre is the control (or inside it).
TOPMOST_JS = """(selector) => {
  const e = document.querySelector(selector);
  if (!e) return null;
  const r = e.getBoundingClientRect();
  const hit = document.elementFromPoint((r.left + r.right) / 2, (r.top + r.bottom) / 2);
  return { box: [r.left, r.top, r.right, r.bottom], topmost: hit !== null && e.contains(hit) };
}"""
PANES_JS = """() => {
  const box = (e) => { const r = e.getBoundingClientRect(); return [r.left, r.top, r.right, r.bottom]; };
  const shown = (e) => e && !e.hidden && e.getBoundingClientRect().width > 0;
  const panes = {}, inScene = {};
  for (const id of ['teleop-toolbar', 'teleop-pane-guide', 'teleop-pane-scene', 'teleop-code']) {
    const e = document.getElementById(id); if (shown(e)) panes[id] = box(e);
  }
  const hud = document.getElementById('teleop-hud'), panel = document.querySelector('[data-testid="floating-panel"]');
  if (shown(hud)) inScene.hud = box(hud);
  if (shown(panel)) inScene.panel = box(panel);
  return { panes, inScene };
}"""
# The drone's scene node projected with viser's camera: CSS pixels in the window, whether it is in
# front of the camera, and whether the canvas is the topmost element there.
DRONE_ON_SCREEN_JS = """() => {
  const t = window.__teleop, v = window.__viserMutable;
  const node = t.scene.ref(t.scene.vehicle.node);
  const p = node.getWorldPosition(v.camera.position.clone());
  v.camera.updateMatrixWorld();
  const ndc = p.project(v.camera);
  const r = v.canvas.getBoundingClientRect();
  const x = r.left + (ndc.x + 1) / 2 * r.width, y = r.top + (1 - ndc.y) / 2 * r.height;
  const hit = document.elementFromPoint(x, y);
  return { x, y, front: ndc.z < 1, canvas: [r.left, r.top, r.right, r.bottom],
           topmost: hit !== null && hit.tagName === 'CANVAS' && document.getElementById('root').contains(hit),
           view: t.scene.view.name, follow: t.scene.follow, switches: t.autoview.switches };
}"""


@pytest.fixture(scope="module")
def lab_server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[LabServer]:
    server = LabServer(
        ["--launch", "all", "start_delay:=3600"], tmp_path_factory.mktemp("workbench") / "server.log"
    )
    try:
        server.wait_ready()
        yield server
    finally:
        server.stop()


@contextlib.contextmanager
def screenshot_on_failure(page: Page, folder: Path, name: str) -> Iterator[None]:
    try:
        yield
    except BaseException:
        with contextlib.suppress(Exception):
            page.screenshot(path=str(folder / name))
            print(f"screenshot {name} in {folder}")
        raise


def open_code_view(page: Page) -> None:
    page.locator("#teleop-code-tab").click()
    page.wait_for_function("() => window.__teleop.codeview.loaded", timeout=EDITOR_LOAD_MS)
    page.locator("#teleop-code .cm-content").wait_for()
    wait_frames(page)


def overlaps(boxes: dict[str, list[float]]) -> list[tuple[str, str]]:
    def meet(a: list[float], b: list[float]) -> bool:
        return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]

    return [(a, b) for a, b in itertools.combinations(sorted(boxes), 2) if meet(boxes[a], boxes[b])]


def inside(inner: list[float], outer: list[float]) -> bool:
    return inner[0] >= outer[0] and inner[1] >= outer[1] and inner[2] <= outer[2] and inner[3] <= outer[3]


@pytest.mark.parametrize("size", SIZES, ids=[f"{w}x{h}" for w, h in SIZES])
def test_workbench_with_code_open_shows_the_scene_and_the_reset_without_overlaps(
    chromium: Browser, lab_server: LabServer, size: tuple[int, int], screenshot_dir: Path
) -> None:
    width, height = size
    window = [0.0, 0.0, float(width), float(height)]
    with (
        lab_page(chromium, {"width": width, "height": height}) as page,
        screenshot_on_failure(page, screenshot_dir, f"workbench_{width}x{height}.png"),
    ):
        open_lab_page(page, lab_server, settle_ms=0)
        open_code_view(page)
        page.evaluate("window.__teleop.layout.layout()")
        share = page.evaluate(SCENE_SHARE_JS, list(GRID))
        reset = page.evaluate(TOPMOST_JS, "#teleop-reset-rocket")
        layout = page.evaluate(PANES_JS)
        print(f"\n{width}x{height}: {share:.1%} of the window shows the scene with the code view open")

        assert share >= LEAST_SCENE, f"{share:.1%} of the window shows the scene"
        assert reset is not None and inside(reset["box"], window) and reset["topmost"], reset
        panes = layout["panes"]
        assert {"teleop-toolbar", "teleop-pane-guide", "teleop-pane-scene", "teleop-code"} <= set(panes), (
            panes
        )
        assert overlaps(panes) == [], panes
        assert all(inside(box, window) for box in panes.values()), panes
        scene_pane = panes["teleop-pane-scene"]
        assert all(inside(box, scene_pane) for box in layout["inScene"].values()), layout
        assert overlaps(layout["inScene"]) == [], layout["inScene"]

        page.locator("#teleop-reset-rocket").click()  # a real click, at the control's centre
        page.wait_for_selector('#teleop-reset-rocket[data-done="ok"]', timeout=ROCKET_RESET_WAIT_MS)


def publish(server: LabServer, target: tuple[float, float, float]) -> str:
    """A publisher of ``target`` on /uav/input/position at 1 Hz, as README shows; its id."""
    body = {"topic": "/uav/input/position", "msg": dict(zip("xyz", target, strict=True)), "rate_hz": 1}
    reply = HTTP.post(f"{server.url}/api/publishers", json=body, timeout=HTTP_TIMEOUT_S)
    assert reply.status_code in (200, 201), reply.text
    return str(reply.json()["id"])


def test_publisher_flying_the_drone_switches_the_view_to_it_without_a_click(
    chromium: Browser, lab_server: LabServer, screenshot_dir: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    width, height = 1366, 768
    with (
        lab_page(chromium, {"width": width, "height": height}) as page,
        screenshot_on_failure(page, screenshot_dir, "workbench_follows_the_drone.png"),
    ):
        open_lab_page(page, lab_server)
        wait_until(lambda: math.dist(position(lab_server), HOME_M) < ARRIVED_M, "the drone at home")
        open_code_view(page)
        first = page.evaluate("window.__teleop.scene.view.name")
        page.wait_for_function("() => window.__teleop.autoview.rest !== null")  # the page saw it rest
        publisher = publish(lab_server, FAR_M)
        try:
            wait_until(
                lambda: math.dist(position(lab_server), FAR_M) < ARRIVED_M,
                "the drone at (5, 5, 10)",
                FLIGHT_WAIT_S,
            )
            wait_stopped(lab_server)
            wait_frames(page, 20)  # the follow camera catches up (0.15 s behind the drone)
            seen = page.evaluate(DRONE_ON_SCREEN_JS)
            png = page.screenshot()
            page.locator("#teleop-hud").get_by_role("button", name="arena", exact=True).click()
            # The page's own state first: the camera held still on the drone's view, then drawn.
            page.wait_for_function(
                "() => !window.__teleop.scene.follow && window.__teleop.scene.view.name === 'Quadrotor'",
                timeout=VIEW_WAIT_MS,
            )
            wait_frames(page, 10)
            arena = find_drone(CanvasShot.of(page, page.screenshot()))
        finally:
            HTTP.delete(f"{lab_server.url}/api/publishers/{publisher}", timeout=HTTP_TIMEOUT_S)
            HTTP.post(
                f"{lab_server.url}/api/publish",
                json={"topic": "/uav/input/position", "msg": dict(zip("xyz", HOME_M, strict=True))},
                timeout=HTTP_TIMEOUT_S,
            )
        drone = find_drone(CanvasShot.of(page, png))

        assert first == "Rocket", first  # the page opened on the rocket waiting for its countdown
        assert (seen["view"], seen["follow"], seen["switches"]) == ("Quadrotor", True, 1), seen
        left, top, right, bottom = seen["canvas"]
        assert seen["front"] and left <= seen["x"] <= right and top <= seen["y"] <= bottom, seen
        assert seen["topmost"], seen  # no pane or overlay over the drone
        assert_drone_seen(drone, "the drone at (5, 5, 10), followed")
        size = (right - left, bottom - top)
        for axis in (0, 1):  # followed, the drone stays near the middle of the scene
            assert abs(drone.centre[axis] - size[axis] / 2) < CENTRED * size[axis], (drone, size)
        # Held still, the arena camera sees the drone up and to the right of the hover point, smaller.
        assert_drone_seen(arena, "the drone at (5, 5, 10), from the arena camera")
        assert arena.centre[0] > size[0] / 2 and arena.centre[1] < size[1] / 2, (arena, size)
        assert arena.hub_px < drone.hub_px
