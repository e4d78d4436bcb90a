"""A world on a world worker, flown through the class server's page like a local one: the class
server hosts no world itself (``--local-worlds 0``), so the student's world goes to the worker
process; the page, its 3D view, key channel and pose stream all come through the class server."""

from __future__ import annotations

import math
from collections.abc import Iterator
from pathlib import Path

import pytest
from labpage import lab_page, wait_until
from labserver import LabServer
from playwright.sync_api import Browser
from support.app import WorldWorker, instructor_token, wait_for_workers
from support.http import HTTP
from test_classroom_browser import HOME_M, HOME_WAIT_S, MOVED_M, PRESSES, SMALL, STILL_M, Student

pytestmark = pytest.mark.browser

CODE = "WORK42"


@pytest.fixture(scope="module")
def class_with_worker(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[LabServer, str]]:
    root: Path = tmp_path_factory.mktemp("world_worker_browser")
    server = LabServer(
        ["--classroom", "--class-code", CODE, "--launch", "fly", "--local-worlds", "0", "--no-foxglove"],
        root / "server.log",
    )
    worker: WorldWorker | None = None
    try:
        server.wait_ready()
        instructor = instructor_token(server.log_tail(10**6))
        worker = WorldWorker(root, f"127.0.0.1:{server.zenoh_port}", instructor, "worker1")
        wait_for_workers(server.url, instructor, {"worker1"})
        yield server, instructor
    finally:
        if worker is not None:
            worker.stop()
        server.stop()


def test_a_workers_world_is_flown_with_the_arrow_keys_through_the_class_servers_page(
    chromium: Browser, class_with_worker: tuple[LabServer, str]
) -> None:
    server, instructor = class_with_worker
    with lab_page(chromium, SMALL) as page:
        ada = Student(page, server, "Ada", CODE).ready()  # the 3D view and the key channel are up
        worlds = HTTP.get(
            f"{server.url}/api/classroom/worlds",
            headers={"Authorization": f"Bearer {instructor}"},
            timeout=10,
        ).json()["worlds"]
        assert [(w["world"], w["worker"]) for w in worlds] == [("ada", "worker1")]
        wait_until(lambda: math.dist(ada.position(), HOME_M) < STILL_M, "ada's drone at home", HOME_WAIT_S)
        before = ada.position()
        for _ in range(PRESSES):
            page.keyboard.press("ArrowRight")
        wait_until(lambda: ada.position()[0] - before[0] > MOVED_M, "ada's drone to move right")
        for _ in range(PRESSES):
            page.keyboard.press("PageUp")
        wait_until(lambda: ada.position()[2] - before[2] > MOVED_M, "ada's drone to climb")
