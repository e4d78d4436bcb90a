"""A class server whose worlds live on a world worker it started itself (``--workers 1
--local-worlds 0``), one process each on loopback for the module: the worker's worlds in the
instructor's checkpoint table, its CSV and the reports' zip; their progress in the class's state
folder, kept by a reset and removed with the student; and a worker that stops answering (SIGSTOP to
its id) turns its worlds' rows unreachable while the routes still answer 200."""

from __future__ import annotations

import contextlib
import csv
import io
import os
import signal
import zipfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import httpx
import pytest
from support.app import App, instructor_token, wait_for_workers
from support.http import HTTP

from server.classroom.remote_checkpoints import ASK_TIMEOUT_S
from server.world.checkpoints.store import PROGRESS_DIR, PROGRESS_FILE

CODE = "KEEP42"
BOUND_S = 3 * ASK_TIMEOUT_S  # well past one bounded ask; a hang would run into it
TABLE = "/api/classroom/checkpoints"


class Class:
    def __init__(self, root: Path) -> None:
        self.state = root / "state"
        self.app = App(
            root,
            "--classroom",
            "--class-code",
            CODE,
            "--launch",
            "rocket",
            "--no-foxglove",
            "--local-worlds",
            "0",
            "--workers",
            "1",
            "--worker-timeout",
            "120",
            "--state-dir",
            str(self.state),
        )
        self.teacher = {"Authorization": f"Bearer {instructor_token(self.app.log_tail(10**6))}"}

    def join(self, name: str) -> tuple[str, dict[str, str]]:
        reply = HTTP.post(f"{self.app.url}/api/classroom/join", json={"name": name, "code": CODE}, timeout=60)
        assert reply.status_code == 201, reply.text
        return reply.json()["world"], {"Authorization": f"Bearer {reply.json()['token']}"}

    def teach(self, method: str, path: str, **params: Any) -> httpx.Response:
        return HTTP.request(method, self.app.url + path, headers=self.teacher, params=params, timeout=BOUND_S)

    def row(self, world: str) -> dict[str, Any]:
        reply = self.teach("GET", TABLE)
        assert reply.status_code == 200, reply.text
        return next(s for s in reply.json()["students"] if s["world"] == world)

    def worker_pid(self) -> int:
        (worker,) = self.teach("GET", "/api/classroom/workers").json()["started_here"]
        return int(worker["pid"])


@pytest.fixture(scope="module")
def klass(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Class]:
    started = Class(tmp_path_factory.mktemp("class_workers"))
    pids: set[int] = set()
    try:
        wait_for_workers(started.app.url, started.teacher["Authorization"][7:], {"local-1"})
        pids.add(started.worker_pid())
        yield started
    finally:
        for pid in pids:  # a worker a test stopped must be able to end with its class server
            with contextlib.suppress(ProcessLookupError):
                os.kill(pid, signal.SIGCONT)
        started.app.stop()


def test_worker_world_in_table_csv_and_zip_kept_by_a_reset_removed_with_the_student(klass: Class) -> None:
    world, ada = klass.join("Ada")
    worlds = {w["world"]: w for w in klass.teach("GET", "/api/classroom/worlds").json()["worlds"]}
    assert worlds[world]["worker"] == "local-1"
    put = HTTP.put(
        f"{klass.app.url}/api/checkpoints/answers/q1", json={"text": "=four nodes"}, headers=ada, timeout=10
    )
    assert put.status_code == 200, put.text

    row = klass.row(world)
    assert row["name"] == "Ada" and row["answers"]["q1"] == "=four nodes"
    assert {c["state"] for c in row["cells"].values()} <= {"not_started", "in_progress"}
    text = klass.teach("GET", TABLE, format="csv").text
    (line,) = [r for r in csv.reader(io.StringIO(text)) if r[1:2] == [world]]
    assert line[0] == "Ada" and "'=four nodes" in line  # as a spreadsheet shows it, never a formula
    archive = zipfile.ZipFile(io.BytesIO(klass.teach("GET", f"{TABLE}/reports").content))
    assert {f"{world}.json", f"{world}.html"} <= set(archive.namelist())
    assert b"=four nodes" in archive.read(f"{world}.json")

    # The worker keeps the world's progress in the class's state folder (the class server's --state-dir).
    saved = klass.state / PROGRESS_DIR / world / PROGRESS_FILE
    assert "=four nodes" in saved.read_text()
    assert klass.teach("POST", f"/api/classroom/worlds/{world}/reset").status_code == 200
    assert klass.row(world)["answers"]["q1"] == "=four nodes" and saved.exists()

    # Removing a world nobody has is a 404 and removes nothing; removing the student removes theirs.
    decoy = klass.state / PROGRESS_DIR / "nobody" / PROGRESS_FILE
    decoy.parent.mkdir()
    decoy.write_text("{}")
    assert klass.teach("DELETE", "/api/classroom/worlds/nobody").status_code == 404
    assert decoy.exists() and saved.exists()
    assert klass.teach("DELETE", f"/api/classroom/worlds/{world}").status_code == 200
    assert not saved.parent.exists()


def test_a_worker_that_does_not_answer_makes_its_rows_unreachable_in_bounded_time(klass: Class) -> None:
    world, _bob = klass.join("Bob")
    assert klass.row(world)["cells"]["fly_to_point"]["state"] == "not_started"
    pid = klass.worker_pid()
    os.kill(pid, signal.SIGSTOP)
    try:
        reply = klass.teach("GET", TABLE)  # its timeout is the bound: a hang fails here
        assert reply.status_code == 200, reply.text
        view = reply.json()
        row = next(s for s in view["students"] if s["world"] == world)
        assert {c["state"] for c in row["cells"].values()} == {"unreachable"}, row
        assert "local-1" in row["unreachable"] and "local-1" in view["worker_errors"]
        text = klass.teach("GET", TABLE, format="csv").text
        (line,) = [r for r in csv.reader(io.StringIO(text)) if r[1:2] == [world]]
        assert line[0] == "Bob" and "unreachable" in line
        zipped = klass.teach("GET", f"{TABLE}/reports")
        assert zipped.status_code == 200
        names = zipfile.ZipFile(io.BytesIO(zipped.content)).namelist()
        assert f"{world}.unreachable.txt" in names and f"{world}.json" not in names
    finally:
        os.kill(pid, signal.SIGCONT)
