"""The code view in a real headless Chromium, against ``python -m server`` on a workspace of its own.

The handout's part 2 from the page alone: make the ``simple_control`` package, type the keyboard
manager into the editor, run it, see its log line, fly the drone a metre with an arrow key
through it, stop it (it leaves the graph), reload: the file is still there. Arrows typed in the
editor never reach the keyboard (a marker key from the 3D view proves that nothing of them
arrived). Saves that fail keep the text; a save over another tab's is refused and offered as a
choice; a file changed on disk shows in the editor; a traceback's line opens its file.

The lab runs the fly launch's nodes without its keyboard manager, so the only node turning keys
into setpoints is the one written here. One server for the module; the first test has a page of
its own (it reloads it), the others share one.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterator
from typing import Any

import httpx
import pytest
from labpage import HTTP_TIMEOUT_S, LOAD_WAIT_MS, lab_page, open_lab_page, position, topic, wait_until
from labserver import LabServer
from playwright.sync_api import Browser, Page, Route
from support.http import HTTP

pytestmark = pytest.mark.browser

# fly.launch without its keyboard_manager_node: the student's node is the one that flies.
DRONE_LAUNCH = """<?xml version="1.0"?>
<launch>
  <include file="$(find-pkg-share visualizer)/launch/view.launch"/>
  <include file="$(find-pkg-share flightcontroller)/launch/position.launch"/>
  <include file="$(find-pkg-share flightcontroller)/launch/velocity.launch"/>
  <include file="$(find-pkg-share flightcontroller)/launch/angle.launch"/>
  <include file="$(find-pkg-share sensor_simulation)/launch/sensors.launch"/>
  <node pkg="flightgoggles" exec="flightgoggles_uav_dynamics" name="flightgoggles_uav_dynamics" output="screen"/>
  <node name="keyboard" pkg="keyboard" exec="keyboard" output="screen"/>
</launch>
"""

# The handout's part 2 keyboard manager with its TODOs filled in (and a log line when it is ready).
KEYBOARD_MANAGER = """import time

import rclpy
from geometry_msgs.msg import Vector3
from keyboard_msgs.msg import Key
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node


class KeyboardManager(Node):
    def __init__(self):
        super().__init__('KeyboardManagerNode')
        self.position_pub = self.create_publisher(Vector3, '/uav/input/position', 1)
        self.keyboard_sub = self.create_subscription(Key, '/keydown', self.get_key, 1)
        self.pos = Vector3()
        self.pos.z = 3.0
        self.pos.x, self.pos.y = 0.0, 0.0
        self.key_code = -1
        time.sleep(1)
        self.timer = self.create_timer(1.0 / 20, self.mainloop)
        self.get_logger().info('keyboard manager ready')

    def get_key(self, msg):
        self.key_code = msg.code

    def mainloop(self):
        self.position_pub.publish(self.pos)
        if self.key_code == Key.KEY_RIGHT:
            self.pos.x += 1.0
        elif self.key_code == Key.KEY_LEFT:
            self.pos.x -= 1.0
        elif self.key_code == Key.KEY_UP:
            self.pos.y += 1.0
        elif self.key_code == Key.KEY_DOWN:
            self.pos.y -= 1.0
        self.key_code = -1


def main():
    rclpy.init()
    try:
        rclpy.spin(KeyboardManager())
    except (ExternalShutdownException, KeyboardInterrupt):
        pass
    finally:
        rclpy.try_shutdown()


if __name__ == '__main__':
    main()
"""
NODE_FILE = "src/simple_control/simple_control/keyboard_manager.py"
NODE = "/KeyboardManagerNode"
EDITOR_LOAD_MS = 60_000
RUN_WAIT_S = 60.0  # a node process starts in about 4 s on a loaded 2-core machine
FLIGHT_WAIT_S = 30.0
ARRIVED_M = 0.2


@pytest.fixture(scope="module")
def server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[LabServer]:
    root = tmp_path_factory.mktemp("editor")
    (root / "drone.launch").write_text(DRONE_LAUNCH)
    (root / "workspace").mkdir()
    lab = LabServer(
        ["--launch", str(root / "drone.launch"), "--workspace", str(root / "workspace")], root / "server.log"
    )
    try:
        lab.wait_ready()
        yield lab
    finally:
        lab.stop()


@pytest.fixture
def page(chromium: Browser) -> Iterator[Page]:
    with lab_page(chromium) as page:
        yield page


@pytest.fixture(scope="module")
def code_page(chromium: Browser, server: LabServer) -> Iterator[Page]:
    """One lab page with its code view open, for the tests that need no fresh page (a load of
    viser's page costs tens of seconds on a loaded machine)."""
    with lab_page(chromium) as page:
        open_lab_page(page, server, settle_ms=0)
        open_code_view(page)
        yield page


def api(server: LabServer, method: str, path: str, **kwargs: Any) -> httpx.Response:
    return HTTP.request(method, f"{server.url}{path}", timeout=HTTP_TIMEOUT_S, **kwargs)


def file_text(server: LabServer, path: str) -> str:
    response = api(server, "GET", f"/api/workspace/files/{path}")
    response.raise_for_status()
    return str(response.json()["text"])


def nodes(server: LabServer) -> set[str]:
    return {str(n["name"]) for n in api(server, "GET", "/api/nodes").json()}


def setpoint(server: LabServer) -> tuple[float, float, float] | None:
    latest = topic(server, "/uav/input/position")["latest"]
    return None if latest is None else (latest["x"], latest["y"], latest["z"])


def open_code_view(page: Page) -> None:
    page.locator("#teleop-code-tab").click()
    page.wait_for_function("() => window.__teleop.codeview.loaded", timeout=EDITOR_LOAD_MS)
    page.locator("#teleop-code .cm-content").wait_for()


def save_state(page: Page) -> str:
    return str(page.locator("#teleop-code .save-state").get_attribute("data-state"))


def replace_text(page: Page, text: str) -> None:
    """Select all in the editor and put ``text`` in its place, as a paste would."""
    page.locator("#teleop-code .cm-content").click()
    page.keyboard.press("Control+a")
    page.keyboard.press("Delete")
    page.keyboard.insert_text(text)


def focus_3d_view(page: Page) -> None:
    """Click a spot of the 3D view that no overlay covers (the guide, the HUD, the code view's tab):
    the first of a few points along its lower half where the page's topmost element is its canvas."""
    spot = page.evaluate(
        """() => {
            const box = document.getElementById("root").getBoundingClientRect();
            for (const fy of [0.75, 0.6, 0.9, 0.5]) {
                for (const fx of [0.6, 0.5, 0.7, 0.4, 0.8]) {
                    const x = box.left + box.width * fx, y = box.top + box.height * fy;
                    const hit = document.elementFromPoint(x, y);
                    if (hit instanceof HTMLCanvasElement) return [x, y];
                }
            }
            return null;
        }"""
    )
    assert spot is not None, "no spot of the 3D view is free of overlays"
    page.mouse.click(spot[0], spot[1])


def wait_setpoint(server: LabServer, expected: tuple[float, float, float], timeout_s: float = 15.0) -> None:
    wait_until(lambda: setpoint(server) == expected, f"the setpoint at {expected}", timeout_s)


def test_editor_simple_control_written_run_flown_stopped_and_kept_across_a_reload(
    server: LabServer, page: Page
) -> None:
    scripts: list[str] = []
    page.on("request", lambda r: scripts.append(r.url) if r.resource_type == "script" else None)
    open_lab_page(page, server, settle_ms=0)
    assert not [u for u in scripts if u.endswith("/static/build/editor.js")], (
        "the editor loaded with the page"
    )
    open_code_view(page)
    assert [u for u in scripts if u.endswith("/static/build/editor.js")], "the editor's own bundle"
    page.get_by_role("button", name="New package").click()
    dialog = page.locator("#teleop-code dialog")
    dialog.locator("input[name=name]").fill("simple_control")
    dialog.locator("input[name=node_name]").fill("keyboard_manager")
    dialog.get_by_role("button", name="Create").click()
    page.locator("#teleop-code .file-bar .path", has_text=NODE_FILE).wait_for()
    assert page.locator(f'#teleop-code .tree [data-path="{NODE_FILE}"]').count() == 1

    replace_text(page, KEYBOARD_MANAGER)
    wait_until(
        lambda: save_state(page) == "saved" and file_text(server, NODE_FILE) == KEYBOARD_MANAGER,
        "the typed file saved",
    )

    # Each state the run shows, with whether its node was in the output's "in the graph" note then.
    page.evaluate(
        """() => {
          const state = document.querySelector('#teleop-code .run-state');
          window.__runStates = [];
          new MutationObserver(() => window.__runStates.push([state.dataset.state,
            document.querySelectorAll('#teleop-code .output .note.joined').length]))
            .observe(state, { attributes: true, attributeFilter: ['data-state'] });
        }"""
    )
    page.get_by_role("button", name="\u25b6 Run").click()
    log_line = page.locator("#teleop-code .output .line.log-info", has_text="keyboard manager ready")
    log_line.wait_for(timeout=RUN_WAIT_S * 1000)
    assert "[KeyboardManagerNode]" in log_line.inner_text()
    assert NODE in nodes(server)
    # Starting until its node is in the graph, as the output says; running from then on.
    page.locator('#teleop-code .run-state[data-state="running"]').wait_for(timeout=RUN_WAIT_S * 1000)
    states = page.evaluate("window.__runStates")
    assert states[0] == ["starting", 0] and states[-1] == ["running", 1], states
    assert [s for s, _ in states] == ["starting"] * (len(states) - 1) + ["running"], states
    started = page.locator("#teleop-code .output .note.started").inner_text()
    assert re.fullmatch(r"\[INFO\] \[[\w.-]+\]: process started with pid \[\d+\]", started), started
    assert page.locator("#teleop-code .output .note.joined").inner_text().endswith(f"in the graph: {NODE}")
    wait_setpoint(server, (0.0, 0.0, 3.0))

    # Arrows typed in the editor move its cursor, never the drone.
    page.locator("#teleop-code .cm-content").click()
    for key in ["ArrowRight", "ArrowRight", "ArrowUp", "ArrowLeft"]:
        page.keyboard.press(key)
    focus_3d_view(page)
    page.keyboard.press("ArrowRight")  # the marker: the only key of all these that flies
    wait_setpoint(server, (1.0, 0.0, 3.0))
    wait_until(
        lambda: math.dist(position(server), (1.0, 0.0, 3.0)) < ARRIVED_M,
        "the drone 1 m along +x",
        FLIGHT_WAIT_S,
    )
    assert setpoint(server) == (1.0, 0.0, 3.0), "a key typed in the editor reached the keyboard"

    page.get_by_role("button", name="\u25a0 Stop").click()
    page.locator('#teleop-code .run-state[data-state="ended"]').wait_for(timeout=RUN_WAIT_S * 1000)
    assert page.locator("#teleop-code .output .note.exit").count() >= 1
    wait_until(lambda: NODE not in nodes(server), "the stopped node to leave the graph", RUN_WAIT_S)

    page.reload(wait_until="commit")
    page.wait_for_function(
        "() => window.__teleop !== undefined", timeout=LOAD_WAIT_MS
    )  # the code view needs no 3D view
    # It was open: the reload opens it again, with no click.
    page.wait_for_function("() => window.__teleop.codeview.loaded", timeout=EDITOR_LOAD_MS)
    assert page.locator("#teleop-code").is_visible()
    assert page.locator("#teleop-code-tab").get_attribute("aria-pressed") == "true"
    page.locator(f'#teleop-code .tree [data-path="{NODE_FILE}"]').click()
    page.locator("#teleop-code .cm-content", has_text="class KeyboardManager(Node):").wait_for()
    assert save_state(page) == "saved"
    assert file_text(server, NODE_FILE) == KEYBOARD_MANAGER
    # Closed, it stays closed across the next reload.
    page.locator("#teleop-code-tab").click()
    assert page.locator("#teleop-code").is_hidden()
    page.reload(wait_until="commit")
    # The workbench is built after the code view has its panel, and opened it if it was open.
    page.wait_for_function("() => document.getElementById('teleop-workbench') !== null", timeout=LOAD_WAIT_MS)
    assert page.evaluate("window.__teleop.codeview.open") is False
    assert page.locator("#teleop-code").is_hidden()


def put(server: LabServer, path: str, text: str) -> str:
    """Save ``path`` as another tab (or an editor on disk) would; its new etag."""
    current = api(server, "GET", f"/api/workspace/files/{path}")
    headers = {"If-Match": current.json()["etag"]} if current.status_code == 200 else {"If-None-Match": "*"}
    response = api(server, "PUT", f"/api/workspace/files/{path}", json={"text": text}, headers=headers)
    response.raise_for_status()
    return str(response.json()["etag"])


def test_editor_save_failure_keeps_text_and_another_tabs_save_is_a_choice(
    server: LabServer, code_page: Page
) -> None:
    page = code_page
    path = "src/scratch/notes.py"
    put(server, path, "first = 1\n")
    page.locator(f'#teleop-code .tree [data-path="{path}"]').click()
    editor = page.locator("#teleop-code .cm-content")
    editor.filter(has_text="first = 1").wait_for()

    # A change on disk while nothing here is unsaved: the editor takes it.
    put(server, path, "changed_on_disk = 2\n")
    editor.filter(has_text="changed_on_disk = 2").wait_for()

    # A save that fails says so and keeps the text; the next edit saves it.
    url = f"**/api/workspace/files/{path}"
    page.route(url, lambda route: route.abort() if route.request.method == "PUT" else route.continue_())
    replace_text(page, "kept = 3\n")
    page.locator('#teleop-code .save-state[data-state="failed"]').wait_for()
    assert "Not saved" in page.locator("#teleop-code .problem").first.inner_text()
    assert file_text(server, path) == "changed_on_disk = 2\n"
    page.unroute(url)
    page.keyboard.insert_text("# again\n")
    wait_until(lambda: file_text(server, path) == "kept = 3\n# again\n", "the kept text saved")

    # Another tab saves just before this page does: refused, and the choice is offered.
    def other_tab_first(route: Route) -> None:
        if route.request.method != "PUT":
            route.continue_()
            return
        put(server, path, "theirs = 4\n")
        route.fulfill(response=route.fetch())  # this page's save, as it sent it, after theirs

    for choice, mine, expected in [
        ("Overwrite with mine", "mine = 5\n", "mine = 5\n"),
        ("Reload theirs", "mine = 6\n", "theirs = 4\n"),
    ]:
        page.route(url, other_tab_first)
        replace_text(page, mine)
        conflict = page.locator("#teleop-code .problem.conflict")
        conflict.wait_for()
        page.unroute(url)
        assert save_state(page) == "conflict"
        assert file_text(server, path) == "theirs = 4\n", "the refused save changed the file"
        conflict.get_by_role("button", name=choice).click()
        page.locator('#teleop-code .save-state[data-state="saved"]').wait_for()
        assert file_text(server, path) == expected
        editor.filter(has_text=expected.strip()).wait_for()


CRASHER = """def main():
    for i in range(20000):
        print('line', i)
    raise RuntimeError('sensor unplugged')


if __name__ == '__main__':
    main()
"""


def test_editor_output_counts_drops_shows_the_exit_and_links_a_traceback_to_its_line(
    server: LabServer, code_page: Page
) -> None:
    page = code_page
    path = "src/crashes/crasher.py"  # a folder without a package.xml: every .py file runs
    put(server, path, CRASHER)
    page.locator(f'#teleop-code .tree [data-path="{path}"]').click()
    page.locator("#teleop-code .file-bar .path", has_text=path).wait_for()
    page.get_by_role("button", name="\u25b6 Run").click()
    page.locator('#teleop-code .run-state[data-state="ended"]').wait_for(timeout=RUN_WAIT_S * 1000)
    output = page.locator("#teleop-code .output")
    assert int(output.get_attribute("data-dropped") or 0) > 0, "20000 lines at once, none dropped"
    assert page.locator("#teleop-code .output .note.dropped").count() == 1
    assert "exited with code 1" in page.locator("#teleop-code .output .note.exit").last.inner_text()
    link = page.locator(f'#teleop-code .output a.traceback[data-path="{path}"]')
    assert link.count() >= 1
    assert link.last.get_attribute("data-line") == str(
        CRASHER.splitlines().index("    raise RuntimeError('sensor unplugged')") + 1
    )
    # The student's line shows; the lab's own frames (rclpy, the launcher), if any, are folded.
    assert link.last.is_visible()
    folds = page.locator("#teleop-code .output details.lab-frames")
    assert all(not fold.get_attribute("open") for fold in folds.all())
    assert folds.locator(f'a.traceback[data-path="{path}"]').count() == 0
    page.get_by_role("button", name="\u25b6 Run").wait_for()
    link.last.click()
    page.locator("#teleop-code .cm-activeLine", has_text="raise RuntimeError('sensor unplugged')").wait_for()


def test_editor_new_file_from_a_template_renamed_then_deleted_after_confirming(
    server: LabServer, code_page: Page
) -> None:
    page = code_page
    put(server, "src/tmpl/package_folder.txt", "a folder for the template\n")
    page.locator('#teleop-code .tree [data-path="src/tmpl"]').click()  # select the folder
    page.get_by_role("button", name="New file").click()
    dialog = page.locator("#teleop-code dialog")
    dialog.locator("select[name=template]").select_option("position_publisher")
    created = "src/tmpl/tmpl/position_publisher.py"  # the template's path, {package} filled in
    assert dialog.locator("input[name=path]").input_value() == created
    dialog.get_by_role("button", name="Create").click()
    page.locator("#teleop-code .file-bar .path", has_text=created).wait_for()
    page.locator("#teleop-code .cm-content", has_text="TODO").wait_for()
    # A long line wraps in the pane (no line runs past the editor's right edge).
    assert page.locator("#teleop-code .cm-content.cm-lineWrapping").count() == 1
    assert page.evaluate("""() => { const c = document.querySelector('#teleop-code .cm-content');
      return [...c.querySelectorAll('.cm-line')].every((l) => l.getBoundingClientRect().right <= c.getBoundingClientRect().right + 1); }""")
    assert "TODO" in file_text(server, created)

    page.get_by_role("button", name="Rename").click()
    renamed = "src/tmpl/tmpl/goal_publisher.py"
    page.locator("#teleop-code dialog input[name=target]").fill(renamed)
    page.locator("#teleop-code dialog").get_by_role("button", name="Rename").click()
    page.locator("#teleop-code .file-bar .path", has_text=renamed).wait_for()
    page.locator(f'#teleop-code .tree [data-path="{renamed}"]').wait_for()
    assert api(server, "GET", f"/api/workspace/files/{created}").status_code == 404

    page.get_by_role("button", name="Delete").click()
    page.locator("#teleop-code dialog").get_by_role("button", name="Cancel").click()  # changes nothing
    assert api(server, "GET", f"/api/workspace/files/{renamed}").status_code == 200
    page.get_by_role("button", name="Delete").click()
    page.locator("#teleop-code dialog").get_by_role("button", name="Delete").click()
    page.locator(f'#teleop-code .tree [data-path="{renamed}"]').wait_for(state="detached")
    assert api(server, "GET", f"/api/workspace/files/{renamed}").status_code == 404
    assert page.locator("#teleop-code .file-bar .path").inner_text() == "no file open"
