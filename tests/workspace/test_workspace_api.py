"""The lab's REST answers about its workspace: where it is (``GET /api/workspace``), and a package
that cannot be used (two with one name) is a 422 naming both, while the lab's own nodes still run."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from server.app import create_app
from server.host.settings import LabSettings, Listening, Settings

from .tutorial_packages import manifest, write


@pytest.fixture
def ws(tmp_path: Path) -> Path:
    write(tmp_path / "src", {"a/twin/package.xml": manifest("twin"), "b/twin/package.xml": manifest("twin")})
    return tmp_path


@pytest.fixture
def client(ws: Path) -> Iterator[TestClient]:
    settings = Settings(
        listen=Listening(allowed_hosts=("testserver",)),
        lab=LabSettings(launch="rocket", launch_args={"start_delay": "3600"}, viewer=False, workspace=ws),
    )
    with TestClient(create_app(settings)) as test_client:
        yield test_client


def test_the_lab_names_its_workspace(client: TestClient, ws: Path) -> None:
    assert client.get("/api/workspace").json() == {"path": str(ws.resolve())}


def test_a_duplicate_package_is_422_naming_both_and_changes_nothing(client: TestClient, ws: Path) -> None:
    nodes = client.get("/api/nodes").json()
    refused = client.post("/api/run", json={"package": "twin", "executable": "x"})
    assert refused.status_code == 422
    assert refused.json()["detail"].endswith(
        f"two packages are named 'twin': {ws / 'src/a/twin'} and {ws / 'src/b/twin'}"
    )
    assert client.get("/api/nodes").json() == nodes
    started = client.post(
        "/api/run", json={"package": "rocketship", "executable": "countdown", "name": "second"}
    )
    assert started.status_code == 201, started.text
