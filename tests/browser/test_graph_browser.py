"""The tools page in a real headless Chromium against a real server: graph, selection, echo, nav link.

The server is ``python -m server --launch rocket`` on a free loopback port, started once for
the module; every wait is bounded (Playwright's own waits, or a polled deadline).
"""

from __future__ import annotations

import os
import shutil
import socket
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import httpx
import pytest
from playwright.sync_api import Browser, ConsoleMessage, Page, Playwright, sync_playwright

pytestmark = pytest.mark.browser

REPO = Path(__file__).resolve().parents[2]
CHROMIUM_FLAGS = [
    "--headless=new", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
    "--disable-component-update", "--disable-sync", "--no-first-run", "--disable-quic",
]  # fmt: skip
SERVER_START_S = 30.0
LAB_NODES = ["/CountDownNode", "/MainControllerNode", "/RocketEngineNode", "/KeyboardManager", "/keyboard"]
LAB_TOPICS = ["/countdown", "/cmd_vel", "/sensor_vel", "/abort_takeoff", "/keydown", "/keyup"]
COUNTDOWN_DELAY_S = 1.0  # the launch's start_delay: after a reset, the first /countdown comes this late
ECHO_WAIT_MS = 15_000


def chromium_path() -> str:
    """Debian's chromium; skipped when missing, except in CI (CI=true), where that is a failure."""
    path = shutil.which("chromium") or ("/usr/bin/chromium" if Path("/usr/bin/chromium").exists() else None)
    if path is None:
        message = "no chromium on PATH (install Debian's 'chromium' to run the browser tests)"
        if os.environ.get("CI") == "true":
            pytest.fail(message)
        pytest.skip(message)
    return path


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


@pytest.fixture(scope="module")
def server_url(tmp_path_factory: pytest.TempPathFactory) -> Iterator[str]:
    port = free_port()
    url = f"http://127.0.0.1:{port}"
    log_path = tmp_path_factory.mktemp("server") / "server.log"
    with log_path.open("w") as log:
        proc = subprocess.Popen(
            [sys.executable, "-m", "server", "--launch", "rocket", "--port", str(port), "--host", "127.0.0.1",
             f"start_delay:={COUNTDOWN_DELAY_S}"],
            cwd=REPO, stdout=log, stderr=subprocess.STDOUT,
        )  # fmt: skip
        try:
            deadline = time.monotonic() + SERVER_START_S
            while not _healthy(url):
                if proc.poll() is not None or time.monotonic() > deadline:
                    pytest.fail(f"the server did not come up:\n{log_path.read_text()[-3000:]}")
                time.sleep(0.1)
            yield url
        finally:
            proc.terminate()
            try:
                proc.wait(timeout=15)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait(timeout=5)


def _healthy(url: str) -> bool:
    try:
        return httpx.get(f"{url}/api/health", timeout=1.0).status_code == 200
    except httpx.HTTPError:
        return False


@pytest.fixture(scope="module")
def playwright() -> Iterator[Playwright]:
    with sync_playwright() as pw:
        yield pw


@pytest.fixture(scope="module")
def browser(playwright: Playwright) -> Iterator[Browser]:
    browser = playwright.chromium.launch(executable_path=chromium_path(), args=CHROMIUM_FLAGS)
    yield browser
    browser.close()


@pytest.fixture
def page(browser: Browser) -> Iterator[Page]:
    """An 800x600 page; page errors and console errors fail the test."""
    context = browser.new_context(viewport={"width": 800, "height": 600})
    page = context.new_page()
    errors: list[str] = []
    page.on("pageerror", lambda exc: errors.append(f"page error: {exc}"))
    page.on("console", lambda msg: _console_error(msg, errors))
    yield page
    context.close()
    assert errors == []


def _console_error(msg: ConsoleMessage, errors: list[str]) -> None:
    if msg.type == "error":
        errors.append(f"console: {msg.text}")


def open_tools(page: Page, server_url: str) -> None:
    page.goto(f"{server_url}/tools")
    page.wait_for_selector('g.graph-node[data-name="/CountDownNode"]')


def test_tools_page_graph_shows_lab_nodes_topics_and_edges(page: Page, server_url: str) -> None:
    open_tools(page, server_url)
    for name in LAB_NODES:
        assert page.locator(f'g.graph-node[data-name="{name}"]').count() == 1, name
    for name in LAB_TOPICS:
        assert page.locator(f'g.graph-topic[data-name="{name}"]').count() == 1, name
    assert page.locator('g.graph-edge[data-from="/CountDownNode"][data-to="/countdown"]').count() == 1
    assert page.locator('g.graph-edge[data-from="/countdown"][data-to="/MainControllerNode"]').count() == 1
    # "Hide debug" is on by default: no hidden nodes, no /rosout.
    assert page.locator('g.graph-topic[data-name="/rosout"]').count() == 0
    assert page.locator('g.graph-node[data-name="/_rocket_view"]').count() == 0
    assert page.locator("#topics-table tbody tr").count() == len(LAB_TOPICS)
    assert page.locator("#nodes-list li").count() == len(LAB_NODES)


def test_tools_page_hide_debug_off_shows_rosout_and_nodes_only_mode_labels_arrows(
    page: Page, server_url: str
) -> None:
    open_tools(page, server_url)
    page.uncheck("#hide-debug")
    page.wait_for_selector('g.graph-topic[data-name="/rosout"]')
    assert page.locator('g.graph-node.debug[data-name="/_rocket_view"]').count() == 1
    page.check("#hide-debug")
    page.wait_for_selector('g.graph-topic[data-name="/rosout"]', state="detached")
    page.select_option("#mode", "nodes")
    page.wait_for_selector("g.graph-topic", state="detached")
    arrow = page.locator('g.graph-edge[data-from="/CountDownNode"][data-to="/MainControllerNode"]')
    assert arrow.locator("text").text_content() == "/countdown"


def test_tools_page_click_node_shows_its_info(page: Page, server_url: str) -> None:
    open_tools(page, server_url)
    page.click('g.graph-node[data-name="/MainControllerNode"]')
    info = page.locator("#node-info")
    info.locator(".publishers >> text=/cmd_vel").wait_for()
    assert info.locator(".title").inner_text() == "/MainControllerNode"
    assert info.locator(".state").inner_text() == "active"
    assert "/countdown" in info.locator(".subscribers").inner_text()


def test_tools_page_click_countdown_shows_type_and_a_live_echo_frame(page: Page, server_url: str) -> None:
    # Restart the countdown, so that it publishes during this test however long the others took.
    assert httpx.post(f"{server_url}/api/rocket/reset", timeout=5.0).status_code == 200
    open_tools(page, server_url)
    page.click('g.graph-topic[data-name="/countdown"]')
    page.locator("#topic-info .facts >> text=std_msgs/msg/Int64").wait_for()
    page.locator('#echo[data-frames]:not([data-frames="0"])').wait_for(timeout=ECHO_WAIT_MS)
    assert '"data"' in page.locator("#echo").inner_text()
    assert "received" in page.locator("#echo-meta").inner_text()
    assert page.locator('g.graph-topic.selected[data-name="/countdown"]').count() == 1


def test_main_page_nav_link_opens_tools_in_new_tab_without_taking_focus(page: Page, server_url: str) -> None:
    page.goto(f"{server_url}/", wait_until="domcontentloaded")  # the 3D view need not finish loading
    link = page.locator("#teleop-nav-tools")
    link.wait_for()
    assert (link.get_attribute("href"), link.get_attribute("target"), link.get_attribute("tabindex")) == (
        "/tools", "_blank", "-1",
    )  # fmt: skip
    with page.context.expect_page() as new_tab:
        link.click(timeout=60_000)  # the 3D view can keep a software-GL main thread busy for seconds
    new_tab.value.wait_for_load_state()
    assert new_tab.value.url == f"{server_url}/tools"
    assert page.evaluate("document.activeElement && document.activeElement.id") != "teleop-nav-tools"


LAYOUT_CASE = """() => {
  const vertices = ["a", "b", "c", "d", "e"].map((id) => ({ id, w: 40 + 10 * id.charCodeAt(0) % 3, h: 20 }));
  const edges = [["a", "b"], ["b", "c"], ["c", "a"], ["a", "d"], ["d", "e"], ["a", "e"], ["d", "d"]]
    .map(([from, to]) => ({ from, to }));
  const out = window.ToolsLayout.layout(vertices, edges);
  return { boxes: Object.fromEntries(out.boxes), routes: out.routes, width: out.width, height: out.height };
}"""


def test_tools_layout_cycle_long_edge_and_self_loop_gives_a_clean_drawing(
    page: Page, server_url: str
) -> None:
    open_tools(page, server_url)
    out = page.evaluate(LAYOUT_CASE)
    boxes = out["boxes"]
    assert sorted(boxes) == ["a", "b", "c", "d", "e"]
    for i, p in enumerate(boxes.values()):  # no two boxes overlap
        for q in list(boxes.values())[i + 1 :]:
            apart_x = abs(p["x"] - q["x"]) >= (p["w"] + q["w"]) / 2
            apart_y = abs(p["y"] - q["y"]) >= (p["h"] + q["h"]) / 2
            assert apart_x or apart_y, (p, q)
    assert all(0 <= b["x"] - b["w"] / 2 and b["x"] + b["w"] / 2 <= out["width"] for b in boxes.values())
    routes = {(r["edge"]["from"], r["edge"]["to"]): r for r in out["routes"]}
    assert routes[("d", "d")]["loop"] is True
    cycle = [routes[e] for e in [("a", "b"), ("b", "c"), ("c", "a")]]
    assert sum(bool(r.get("reversed")) for r in cycle) == 1  # one edge turned back breaks the cycle
    for (source, target), route in routes.items():
        if source == target:
            continue
        first, last = route["points"][0], route["points"][-1]
        assert (first["x"], first["y"]) == (boxes[source]["x"], boxes[source]["y"])
        assert (last["x"], last["y"]) == (boxes[target]["x"], boxes[target]["y"])
        if not route.get("reversed"):
            assert boxes[source]["x"] < boxes[target]["x"]  # left to right
    assert len(routes[("a", "e")]["points"]) > 2  # a long edge bends through its dummy vertices
