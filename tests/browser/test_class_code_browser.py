"""Students' code on a class server in a real headless Chromium: Ada and Bob each write a node in
their page's code view (a new package, the node typed in), saved in their world's workspace, and
run it from the page, sandboxed: each sees their own node's log line and not the other's, and
each world's graph holds its own node only. Bob's code view does not show Ada's file, and his
token cannot read it; the instructor's page opens her workspace read-only (the file's text, no
editor) and downloads every workspace as one zip, a folder per student.

One class server for the module (the rocket alone per world: the code view needs no flight), a
browser context each for Ada, Bob and the instructor. The students' pages are used before their
3D view has loaded: the code view does not wait for it.
"""

from __future__ import annotations

import io
import re
import zipfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import httpx
import pytest
from labpage import HTTP_TIMEOUT_S, LOAD_WAIT_MS, lab_page, wait_until
from labserver import LabServer
from playwright.sync_api import Browser, Page
from support.http import HTTP

pytestmark = pytest.mark.browser

CODE = "CODE42"
SMALL = {"width": 900, "height": 650}
EDITOR_LOAD_MS = 60_000
RUN_WAIT_MS = 60_000
NODE = """import rclpy
from rclpy.node import Node


def main():
    rclpy.init()
    node = Node('{node}')
    node.get_logger().info("{line}")
    rclpy.spin(node)


if __name__ == '__main__':
    main()
"""
ADA_FILE = "src/ada_pkg/ada_pkg/pilot.py"
ADA_LINE = "Ada's pilot ready"
ADA_TEXT = NODE.format(node="pilot", line=ADA_LINE)
BOB_FILE = "src/bob_pkg/bob_pkg/copilot.py"
BOB_LINE = "Bob's copilot ready"
BOB_TEXT = NODE.format(node="copilot", line=BOB_LINE)


@pytest.fixture(scope="module")
def class_server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[LabServer]:
    root = tmp_path_factory.mktemp("class_code")
    server = LabServer(
        [
            "--classroom",
            "--class-code",
            CODE,
            "--launch",
            "rocket",
            "start_delay:=3600",
            "--workspaces-dir",
            str(root / "workspaces"),
        ],
        root / "server.log",
    )
    try:
        server.wait_ready()
        yield server
    finally:
        server.stop()


def join(pages: dict[str, Page], server: LabServer) -> list[str]:
    """Each student joins through the page's form (both at once: their worlds start together);
    their tokens (each page's HTTP-only cookie)."""
    for name, page in pages.items():
        page.goto(server.url + "/", timeout=LOAD_WAIT_MS)
        page.fill("#name", name)
        page.fill("#code", CODE)
    first, second = pages.values()
    # The form reloads the page once the world is up.
    with first.expect_navigation(timeout=LOAD_WAIT_MS), second.expect_navigation(timeout=LOAD_WAIT_MS):
        first.click("#go")
        second.click("#go")
    tokens = []
    for page in pages.values():
        page.wait_for_function("() => window.__teleop !== undefined", timeout=LOAD_WAIT_MS)
        tokens.append({c["name"]: c["value"] for c in page.context.cookies()}["lab_token"])
    return tokens


def open_code_view(page: Page) -> None:
    # The page may still be parsing viser's bundle and drawing its first frames (two at once, in
    # software WebGL): the tab takes the clicks once the page is steady enough for it.
    page.locator("#teleop-code-tab").click(timeout=LOAD_WAIT_MS)
    page.wait_for_function("() => window.__teleop.codeview.loaded", timeout=EDITOR_LOAD_MS)
    page.locator("#teleop-code .cm-content").wait_for()


def api(server: LabServer, token: str, path: str, **headers: str) -> httpx.Response:
    return HTTP.get(
        server.url + path, headers={"Authorization": f"Bearer {token}", **headers}, timeout=HTTP_TIMEOUT_S
    )


def write_node(page: Page, package: str, node: str, path: str, text: str) -> None:
    """A new package with its node from the code view's dialog, the node's text typed over it."""
    page.get_by_role("button", name="New package").click()
    dialog = page.locator("#teleop-code dialog")
    dialog.locator("input[name=name]").fill(package)
    dialog.locator("input[name=node_name]").fill(node)
    dialog.get_by_role("button", name="Create").click()
    page.locator("#teleop-code .file-bar .path", has_text=path).wait_for()
    page.locator("#teleop-code .cm-content").click()
    page.keyboard.press("Control+a")
    page.keyboard.press("Delete")
    page.keyboard.insert_text(text)


def run_until_logged(page: Page, line: str) -> None:
    page.get_by_role("button", name="\u25b6 Run").click()
    page.locator("#teleop-code .output .line.log-info", has_text=line).wait_for(timeout=RUN_WAIT_MS)


def output_of(page: Page) -> str:
    return page.locator("#teleop-code .output").inner_text()


def node_names(server: LabServer, token: str) -> set[str]:
    return {n["name"] for n in api(server, token, "/api/nodes").json()}


def text_of(server: LabServer, token: str, path: str) -> Any:
    reply = api(server, token, f"/api/workspace/files/{path}")
    return reply.json()["text"] if reply.status_code == 200 else None


def test_class_code_is_each_students_own_and_the_instructor_reads_it(
    chromium: Browser, class_server: LabServer
) -> None:
    server = class_server
    with lab_page(chromium, SMALL) as ada, lab_page(chromium, SMALL) as bob, lab_page(chromium) as teacher:
        ada_token, bob_token = join({"Ada": ada, "Bob": bob}, server)

        # Ada: a new package in the code view, her node typed into it, saved, run in her world.
        open_code_view(ada)
        write_node(ada, "ada_pkg", "pilot", ADA_FILE, ADA_TEXT)
        wait_until(lambda: text_of(server, ada_token, ADA_FILE) == ADA_TEXT, "Ada's text saved")
        run_until_logged(ada, ADA_LINE)

        # Bob: his own package; Ada's file is not in his tree and his token cannot read it.
        open_code_view(bob)
        write_node(bob, "bob_pkg", "copilot", BOB_FILE, BOB_TEXT)
        wait_until(lambda: text_of(server, bob_token, BOB_FILE) == BOB_TEXT, "Bob's text saved")
        bob.locator(f'#teleop-code .tree [data-path="{BOB_FILE}"]').wait_for()
        assert bob.locator(f'#teleop-code .tree [data-path="{ADA_FILE}"]').count() == 0
        assert bob.locator("#teleop-code .tree", has_text="ada_pkg").count() == 0
        assert api(server, bob_token, f"/api/workspace/files/{ADA_FILE}").status_code == 404  # not in his
        assert (
            api(server, bob_token, f"/api/workspace/files/{ADA_FILE}", **{"X-Lab-World": "ada"}).status_code
            == 403
        )
        assert api(server, ada_token, f"/api/workspace/files/{ADA_FILE}").json()["text"] == ADA_TEXT

        # Both nodes run at once, each in its own world, each page showing its own output only.
        run_until_logged(bob, BOB_LINE)
        assert ADA_LINE not in output_of(bob) and BOB_LINE not in output_of(ada)
        assert "/pilot" in node_names(server, ada_token) and "/copilot" not in node_names(server, ada_token)
        assert "/copilot" in node_names(server, bob_token) and "/pilot" not in node_names(server, bob_token)
        for page, token, node in ((ada, ada_token, "/pilot"), (bob, bob_token, "/copilot")):
            page.get_by_role("button", name="\u25a0 Stop").click()
            page.locator('#teleop-code .run-state[data-state="ended"]').wait_for(timeout=RUN_WAIT_MS)
            wait_until(lambda: node not in node_names(server, token), f"{node} to leave the graph")  # noqa: B023

        # The instructor: Ada's workspace read-only, then every workspace in one zip.
        found = re.search(r"/instructor\?token=(\S+)", server.log_tail(10**6))
        assert found is not None, "the class server prints the instructor's link once"
        teacher.goto(f"{server.url}/instructor?token={found.group(1)}", timeout=LOAD_WAIT_MS)
        teacher.locator("tr[data-world='ada'] button:text-is('Code')").click()
        box = teacher.locator("#workspace")
        box.locator("#workspace-title", has_text="Ada's workspace (read-only)").wait_for()
        box.get_by_role("button", name=ADA_FILE).click()
        box.locator("#workspace-path", has_text=ADA_FILE).wait_for()
        wait_until(
            lambda: box.locator("#workspace-text").text_content() == ADA_TEXT, "Ada's text in the dialog"
        )
        editable = (
            "#workspace textarea, #workspace input, #workspace [contenteditable], #workspace .cm-editor"
        )
        assert teacher.locator(editable).count() == 0, "the instructor's view offers editing"
        assert box.get_by_role("button", name=re.compile("save", re.IGNORECASE)).count() == 0
        box.get_by_role("button", name="Close").click()

        with teacher.expect_download() as download:
            teacher.locator("#workspaces-zip").click()
        path = download.value.path()
        with zipfile.ZipFile(io.BytesIO(Path(path).read_bytes())) as archive:
            names = archive.namelist()
            assert archive.read(f"ada/{ADA_FILE}").decode() == ADA_TEXT
            assert archive.read(f"bob/{BOB_FILE}").decode() == BOB_TEXT
        assert {name.split("/", 1)[0] for name in names} == {"ada", "bob"}
        assert not [n for n in names if n.startswith("bob/") and "ada_pkg" in n]
