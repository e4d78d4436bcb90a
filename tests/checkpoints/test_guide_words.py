"""The Guide speaks the page: its steps name the page's own controls, as the page draws them, with
the terminal's commands as the alternative; a step the lab's launch already did says so; and no
Guide text shows a path outside the student's workspace, before the student acts or after a launch
file of the workspace ran. Through the real app (TestClient, its lifespan entered)."""

from __future__ import annotations

import json
import re
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient
from support.app import REPO
from support.app_pool import lab_client
from support.wait import wait_until

from server.host.settings import LabSettings, Listening, Settings
from server.world.checkpoints import page_names

PACKAGE_XML = """<?xml version="1.0"?>
<package format="3"><name>drone_keys</name><version>0.0.0</version>
<description>test</description><maintainer email="a@b.c">a</maintainer><license>MIT</license>
<export><build_type>ament_python</build_type></export></package>
"""
LAUNCH = '<launch><node pkg="keyboard" exec="keyboard" name="second_keyboard"/></launch>\n'
_JS_STRING = re.compile(r'"((?:[^"\\\n]|\\.)*)"')


def _js_strings(path: Path) -> set[str]:
    """The double-quoted string literals of a TypeScript file, as the page shows them."""
    return {json.loads(f'"{m}"') for m in _JS_STRING.findall(path.read_text())}


@pytest.fixture(scope="module")
def lab(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[TestClient, Path]]:
    root = tmp_path_factory.mktemp("guide")
    workspace = root / "workspace"
    (workspace / "src/drone_keys/launch").mkdir(parents=True)
    (workspace / "src/drone_keys/package.xml").write_text(PACKAGE_XML)
    (workspace / "src/drone_keys/launch/fly.launch").write_text(LAUNCH)
    settings = Settings(
        listen=Listening(allowed_hosts=("testserver",)),
        lab=LabSettings(
            launch="all",
            launch_args={"start_delay": "3600", "simple": "true"},
            viewer=False,
            state_dir=root / "state",
            workspace=workspace,
        ),
    )
    with lab_client(settings) as client:
        yield client, workspace


def _guide(client: TestClient) -> dict[str, Any]:
    reply = client.get("/api/checkpoints")
    assert reply.status_code == 200, reply.text
    return dict(reply.json())


def _checkpoint(body: dict[str, Any], name: str) -> dict[str, Any]:
    return next(c for c in body["checkpoints"] if c["name"] == name)


def _assert_no_server_path(body: dict[str, Any], workspace: Path) -> None:
    text = json.dumps(body, ensure_ascii=False)
    for path in (
        str(REPO),
        str(workspace.resolve()),
        str(workspace),
        "/server/packages/",
        tempfile.gettempdir(),
    ):
        assert path not in text, f"the Guide shows {path!r}"


def test_guide_the_page_controls_it_names_are_the_pages_own() -> None:
    strings = _js_strings(REPO / "web/src/editor/main.ts")
    assert {page_names.RUN, page_names.NEW_FILE, page_names.NEW_PACKAGE} <= strings
    assert page_names.CODE in _js_strings(REPO / "web/src/lab/codeview.ts")
    assert page_names.GRAPH in _js_strings(REPO / "web/src/lab/nav.ts")
    assert f'"{page_names.RESET_ROCKET}"' in (REPO / "server/peripherals/viewer/rocket_view.py").read_text()
    panel = (REPO / "server/peripherals/viewer/publisher_panel.py").read_text()
    assert all(f'"{n}"' in panel for n in (page_names.PUBLISHER, page_names.RATE, page_names.ENABLED))


def test_guide_steps_of_checkpoints_1_and_2_name_the_page_first(lab: tuple[TestClient, Path]) -> None:
    client, _ = lab
    body = _guide(client)
    abort, fly = _checkpoint(body, "keyboard_abort"), _checkpoint(body, "fly_to_point")
    abort_page = " ".join(s["page"] for s in abort["steps"])
    for name in (page_names.CODE, page_names.RUN, page_names.RESET_ROCKET, page_names.ROCKET_TEMPLATE):
        assert name in abort_page
    fly_page = " ".join(s["page"] for s in fly["steps"])
    for name in (page_names.PUBLISHER, page_names.ENABLED, page_names.POSITION_TEMPLATE, page_names.RUN):
        assert name in fly_page
    # The terminal's way stays, as the alternative, where the page has one too.
    assert any(s["page"] and s["commands"] for s in abort["steps"] + fly["steps"])
    # Under the lab's launch the rocket and the drone already run: those steps say so, and ask nothing.
    assert [s["already"] is not None for s in abort["steps"]] == [False, True, False, False, False]
    assert "already flying" in fly["steps"][0]["already"]


def test_guide_shows_no_path_outside_the_workspace_before_and_after_a_launch(
    lab: tuple[TestClient, Path],
) -> None:
    client, workspace = lab
    _assert_no_server_path(_guide(client), workspace)  # the lab's own launch was seen: named, not a path
    started = client.post("/api/launch", json={"package": "drone_keys", "file": "fly.launch"})
    assert started.status_code == 201, started.text
    wait_until(
        lambda: (
            "src/drone_keys/launch/fly.launch" in _checkpoint(_guide(client), "launch_and_keys")["progress"]
        ),
        "checkpoint 3 to name the workspace's launch file",
        10.0,
    )
    _assert_no_server_path(_guide(client), workspace)
    assert client.delete(f"/api/launches/{started.json()['id']}").status_code == 200
