"""The tools page in a real headless Chromium against a real server: graph, selection, echo, nav link.

Chromium and the server (``python -m server --launch rocket`` on a free loopback port, started
once for the module) come from conftest.py; every wait is bounded (Playwright's own waits).
"""

from __future__ import annotations

from collections.abc import Iterator

import pytest
from labpage import HTTP_TIMEOUT_S, LOAD_WAIT_MS
from labserver import LabServer
from playwright.sync_api import Browser, ConsoleMessage, Page, expect
from support.http import HTTP

pytestmark = pytest.mark.browser

LAB_NODES = ["/CountDownNode", "/MainControllerNode", "/RocketEngineNode", "/KeyboardManager", "/keyboard"]
LAB_TOPICS = ["/countdown", "/cmd_vel", "/sensor_vel", "/abort_takeoff", "/keydown", "/keyup"]
PAGE_WAIT_MS = 30_000  # SwiftShader on 2 cores can keep the main page's thread busy for seconds
ECHO_WAIT_MS = 15_000  # after a reset, the countdown's first message comes start_delay (2 s) later


@pytest.fixture
def server_url(rocket_server: LabServer) -> str:
    return rocket_server.url


@pytest.fixture
def page(chromium: Browser) -> Iterator[Page]:
    """An 800x600 page; page errors and console errors fail the test."""
    context = chromium.new_context(viewport={"width": 800, "height": 600})
    page = context.new_page()
    page.set_default_timeout(PAGE_WAIT_MS)
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
    # The lists are filled just after the drawing: expect() waits for them.
    expect(page.locator("#topics-table tbody tr")).to_have_count(len(LAB_TOPICS))
    expect(page.locator("#nodes-list li")).to_have_count(len(LAB_NODES))


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
    assert HTTP.post(f"{server_url}/api/rocket/reset", timeout=HTTP_TIMEOUT_S).status_code == 200
    open_tools(page, server_url)
    page.click('g.graph-topic[data-name="/countdown"]')
    page.locator("#topic-info .facts >> text=std_msgs/msg/Int64").wait_for()
    page.locator('#echo[data-frames]:not([data-frames="0"])').wait_for(timeout=ECHO_WAIT_MS)
    assert '"data"' in page.locator("#echo").inner_text()
    assert "received" in page.locator("#echo-meta").inner_text()
    assert page.locator('g.graph-topic.selected[data-name="/countdown"]').count() == 1


def test_main_page_nav_link_opens_tools_in_new_tab_without_taking_focus(page: Page, server_url: str) -> None:
    # The 3D view need not finish loading; the main page's first load is slow on a loaded machine.
    page.goto(f"{server_url}/", wait_until="domcontentloaded", timeout=LOAD_WAIT_MS)
    link = page.locator("#teleop-nav-tools")
    link.wait_for(timeout=LOAD_WAIT_MS)
    assert (link.get_attribute("href"), link.get_attribute("target"), link.get_attribute("tabindex")) == (
        "/tools",
        "_blank",
        "-1",
    )
    with page.context.expect_page(timeout=LOAD_WAIT_MS) as new_tab:
        link.click(timeout=LOAD_WAIT_MS)
    new_tab.value.wait_for_load_state(timeout=LOAD_WAIT_MS)
    assert new_tab.value.url == f"{server_url}/tools"
    assert page.evaluate("document.activeElement && document.activeElement.id") != "teleop-nav-tools"


LAYOUT_CASE = """() => {
  const vertices = ["a", "b", "c", "d", "e"].map((id) => ({ id, w: 40 + 10 * id.charCodeAt(0) % 3, h: 20 }));
  const edges = [["a", "b"], ["b", "c"], ["c", "a"], ["a", "d"], ["d", "e"], ["a", "e"], ["d", "d"]]
    .map(([from, to]) => ({ from, to }));
  const out = window.__tools.layout.layout(vertices, edges);
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
    assert all(b["x"] - b["w"] / 2 >= 0 and b["x"] + b["w"] / 2 <= out["width"] for b in boxes.values())
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
