"""A class server through the real app, its worlds on one manual clock: two students at different
checkpoints in the instructor's table, its CSV and the reports' zip; a reset keeps what was met."""

from __future__ import annotations

import asyncio
import csv
import io
import json
import zipfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient

from node_runtime.bus import ManualClock
from server.app import create_app
from server.classroom import ClassServer
from server.host.settings import ClassroomSettings, LabSettings, Listening, Settings

CODE = "CHECK7"
FILE = {"content-type": "application/octet-stream"}


@pytest.fixture(scope="module")
def clock() -> ManualClock:
    return ManualClock(1_000.0)


@pytest.fixture(scope="module")
def client(clock: ManualClock, tmp_path_factory: pytest.TempPathFactory) -> Iterator[TestClient]:
    settings = Settings(
        listen=Listening(allowed_hosts=("testserver",)),
        lab=LabSettings(
            launch="fly",
            launch_args={"simple": "true"},
            viewer=False,
            state_dir=tmp_path_factory.mktemp("state"),
            bag_dir=tmp_path_factory.mktemp("bags"),
        ),
        classroom=ClassroomSettings(code=CODE, max_worlds=2),
    )
    with TestClient(create_app(settings, clock)) as test_client:
        yield test_client


def classroom(client: TestClient) -> ClassServer:
    return client.app.state.classroom  # type: ignore[attr-defined,no-any-return]


def join(client: TestClient, name: str) -> dict[str, str]:
    reply = client.post("/api/classroom/join", json={"name": name, "code": CODE})
    assert reply.status_code == 201, reply.text
    client.cookies.clear()
    return {"Authorization": f"Bearer {reply.json()['token']}"}


def advance(client: TestClient, clock: ManualClock, seconds: float) -> None:
    """Every world's time on together, each timer at its deadline (as the class tests step it)."""
    labs = [w.lab for w in classroom(client).worlds.values() if w.lab is not None]
    end = clock.now() + seconds

    def run() -> None:
        for lab in labs:
            lab.executor.spin_some()
        while (deadline := min(lab.executor.next_deadline_s() for lab in labs)) <= end:
            clock.set(max(deadline, clock.now()))
            for lab in labs:
                lab.executor.spin_some()
        clock.set(max(end, clock.now()))
        for lab in labs:
            lab.executor.spin_some()

    assert client.portal is not None
    client.portal.call(run)


def publish_to_target(client: TestClient, who: dict[str, str], rate_hz: float) -> None:
    body = {
        "topic": "/uav/input/position",
        "msg": {"x": 5.0, "y": 5.0, "z": 10.0},
        "type": "geometry_msgs/msg/Vector3",
        "rate_hz": rate_hz,
    }
    reply = client.post("/api/publishers", json=body, headers=who)
    assert reply.status_code == 201, reply.text


def cells(view: dict[str, Any], student: str) -> dict[str, Any]:
    return next(s for s in view["students"] if s["name"] == student)["cells"]


def test_two_students_at_different_checkpoints_in_the_table_csv_and_zip(
    client: TestClient, clock: ManualClock
) -> None:
    ada, bob = join(client, "Ada"), join(client, "Bob")
    teacher = {"Authorization": f"Bearer {classroom(client).instructor_token}"}
    publish_to_target(client, ada, 1.0)
    publish_to_target(client, bob, 5.0)
    assert (
        client.put(
            "/api/checkpoints/answers/final", json={"text": "=1+1 one command"}, headers=bob
        ).status_code
        == 200
    )
    for _ in range(8):  # the drones fly to (5, 5, 10) and hold there
        advance(client, clock, 5.0)
    assert client.get("/api/checkpoints", headers=ada).json()["checkpoints"][1]["state"] == "done"

    refused = client.get("/api/classroom/checkpoints", headers=ada)
    assert refused.status_code == 403  # a student does not see the class
    view = client.get("/api/classroom/checkpoints", headers=teacher).json()
    assert view["checkpoints"] == ["keyboard_abort", "fly_to_point", "launch_and_keys"]
    assert (
        cells(view, "Ada")["fly_to_point"]["state"] == "done"
        and cells(view, "Ada")["fly_to_point"]["done_at"]
    )
    assert cells(view, "Bob")["fly_to_point"] == {"state": "in_progress", "done_at": None}
    assert next(s for s in view["students"] if s["name"] == "Bob")["answers"]["final"] == "=1+1 one command"

    table = client.get("/api/classroom/checkpoints", params={"format": "csv"}, headers=teacher)
    assert table.headers["content-type"].startswith("text/csv")
    rows = {r["student"]: r for r in csv.DictReader(io.StringIO(table.text))}
    assert rows["Ada"]["fly_to_point state"] == "done" and rows["Ada"]["fly_to_point done at"]
    assert rows["Bob"]["fly_to_point state"] == "in_progress" and rows["Bob"]["fly_to_point done at"] == ""
    assert rows["Bob"]["final"] == "'=1+1 one command"  # never a formula in a spreadsheet

    zipped = client.get("/api/classroom/checkpoints/reports", headers=teacher)
    with zipfile.ZipFile(io.BytesIO(zipped.content)) as archive:
        assert sorted(archive.namelist()) == ["ada.html", "ada.json", "bob.html", "bob.json"]
        ada_report = archive.read("ada.json")
        bob_page = archive.read("bob.html")
    assert json.loads(ada_report)["student"] == "Ada"
    for report in (ada_report, bob_page):
        verdict = client.post("/api/checkpoints/verify", content=report, headers={**teacher, **FILE}).json()
        assert verdict["valid"] is True, verdict
    assert (
        client.post("/api/checkpoints/verify", content=ada_report, headers={**bob, **FILE}).json()["student"]
        == "Ada"
    )

    # A reset starts Ada's world over; what she met stays met.
    assert client.post("/api/classroom/worlds/ada/reset", headers=ada).status_code == 200
    advance(client, clock, 1.0)
    after = client.get("/api/classroom/checkpoints", headers=teacher).json()
    assert cells(after, "Ada")["fly_to_point"] == cells(view, "Ada")["fly_to_point"]
    assert client.get("/api/checkpoints", headers=ada).json()["checkpoints"][1]["evidence"]["rate_hz"] > 0


def test_class_routes_answer_404_on_a_lab_alone(tmp_path: Path) -> None:
    settings = Settings(
        listen=Listening(allowed_hosts=("testserver",)),
        lab=LabSettings(
            launch="rocket", launch_args={"start_delay": "3600"}, viewer=False, state_dir=tmp_path
        ),
    )
    with TestClient(create_app(settings)) as lab:
        assert lab.get("/api/classroom/checkpoints").status_code == 404
        assert lab.get("/api/checkpoints").status_code == 200


class FakeWorkers:
    """World workers answering GET /api/classroom/checkpoints with a table, or failing."""

    def __init__(self, answers: dict[str, Any]) -> None:
        self.answers = answers

    async def checked(
        self, ref: Any, method: str, path: str, *, world: str | None = None, body: Any = None
    ) -> Any:
        assert (method, path) == ("GET", "/api/classroom/checkpoints")
        answer = self.answers[ref.id]
        if isinstance(answer, Exception):
            raise answer
        if answer is None:  # a worker that never answers
            await asyncio.Event().wait()
        return answer


def test_worker_rows_are_those_of_the_worlds_each_worker_hosts_for_this_class_else_unreachable() -> None:
    from node_runtime.limits import RateLimit
    from server.classroom.errors import WorkerFailedError
    from server.classroom.remote_checkpoints import checkpoint_rows
    from server.classroom.workers import WorkerRef
    from server.classroom.world import World

    def world(name: str, worker: str | None) -> World:
        ref = WorkerRef(worker, f"http://127.0.0.1:1/{worker}", 1, 4, "t") if worker else None
        return World(name, name.title(), "id", None, RateLimit(ManualClock(), 1.0, 1), worker=ref)

    row = {
        "name": "Cy",
        "world": "cy",
        "cells": {"fly_to_point": {"state": "done", "done_at": "x"}},
        "answers": {},
    }
    stray = {**row, "name": "Old", "world": "old"}  # a world that worker hosts, not for this class now
    workers = FakeWorkers(
        {
            "w1": {"checkpoints": [], "students": [row, stray]},
            "w2": WorkerFailedError("gone"),
            "w3": None,
            "w4": "not a table",
        }
    )
    worlds = {
        "cy": world("cy", "w1"),
        "dee": world("dee", "w2"),
        "eve": world("eve", "w3"),
        "fay": world("fay", "w4"),
        "ada": world("ada", None),
    }
    worlds["ada"].lab = object()  # type: ignore[assignment]  # hosted here: the class server's own row
    names = ["fly_to_point", "keyboard_abort"]
    rows, errors = asyncio.run(checkpoint_rows(workers, worlds, names, timeout_s=0.05))  # type: ignore[arg-type]
    assert rows[0] == row and [r["world"] for r in rows] == ["cy", "dee", "eve", "fay"]
    for unreachable in rows[1:]:
        assert unreachable["cells"] == {n: {"state": "unreachable", "done_at": None} for n in names}
        assert unreachable["answers"] == {} and unreachable["name"] == unreachable["world"].title()
    assert "gone" in rows[1]["unreachable"] and "within 0.05 s" in rows[2]["unreachable"]
    assert "not a checkpoint table" in rows[3]["unreachable"]
    assert sorted(errors) == ["w2", "w3", "w4"]
