"""A lab's progress across restarts of its server: ``python -m server --state-dir`` in a subprocess,
checkpoint 2 met by REST with the kinematic sim, an answer and a capture; the process ended by its
id and a new one started on the same state folder finds all of it; one whose file was spoilt
starts with none, says so in its log, and serves all the same."""

from __future__ import annotations

import textwrap
from pathlib import Path
from typing import Any

from support.app import App
from support.http import HTTP
from support.wait import wait_until

from server.world.checkpoints.store import PROGRESS_DIR, PROGRESS_FILE, SINGLE_LAB

from .test_api import tiny_png

FLY_TIMEOUT_S = 60.0
FLY_SIMPLE = """<?xml version="1.0"?>
<launch>
  <include file="$(find-pkg-share flightcontroller)/launch/position.launch">
    <arg name="simple" value="true"/>
  </include>
  <node pkg="simple_sim" exec="simple_sim_node"/>
</launch>
"""
NOTHING = '<?xml version="1.0"?>\n<launch/>\n'  # the restarts only read: no node need start


def start(root: Path, run: str, launch: str = "nothing.launch") -> App:
    (root / run).mkdir()
    return App(
        root / run,
        "--launch",
        str(root / launch),
        "--state-dir",
        str(root / "state"),
        "--no-foxglove",
        cwd=root,
    )


def checkpoint(app: App, name: str) -> dict[str, Any]:
    return next(c for c in app.get("/api/checkpoints")["checkpoints"] if c["name"] == name)


def answer(app: App, qid: str) -> str:
    return str(next(q for q in app.get("/api/checkpoints")["questions"] if q["id"] == qid)["answer"])


def meet_fly_to_point(app: App) -> dict[str, Any]:
    body = {
        "topic": "/uav/input/position",
        "msg": {"x": 5.0, "y": 5.0, "z": 10.0},
        "type": "geometry_msgs/msg/Vector3",
        "rate_hz": 1.0,
    }
    assert app.post("/api/publishers", body).status_code == 201
    found: list[dict[str, Any]] = []

    def done() -> bool:
        found[:] = [checkpoint(app, "fly_to_point")]
        return bool(found[0]["state"] == "done")

    wait_until(done, "fly_to_point done", FLY_TIMEOUT_S, poll_s=0.2, detail=app.log_tail)
    return found[0]


def test_progress_outlives_the_server_process_and_a_spoilt_file_is_none_and_logged(tmp_path: Path) -> None:
    (tmp_path / "fly_simple.launch").write_text(textwrap.dedent(FLY_SIMPLE).lstrip())
    (tmp_path / "nothing.launch").write_text(NOTHING)
    png = tiny_png()
    first = start(tmp_path, "first", "fly_simple.launch")
    try:
        saved = HTTP.put(f"{first.url}/api/checkpoints/answers/q1", json={"text": "four nodes"}, timeout=10)
        assert saved.status_code == 200, saved.text
        captured = HTTP.post(
            f"{first.url}/api/checkpoints/fly_to_point/capture",
            content=png,
            headers={"content-type": "image/png"},
            timeout=10,
        )
        assert captured.status_code == 200, captured.text
        met = meet_fly_to_point(first)
    finally:
        first.stop()  # Ctrl-C to its id: it writes what waits, then ends
    folder = tmp_path / "state" / PROGRESS_DIR / SINGLE_LAB
    assert (folder / "fly_to_point.png").read_bytes() == png

    second = start(tmp_path, "second")
    try:
        again = checkpoint(second, "fly_to_point")
        assert again["state"] == "done" and again["done_at"] == met["done_at"]
        assert again["times_done"] == met["times_done"] and again["evidence"] == met["evidence"]
        assert answer(second, "q1") == "four nodes"
        report = second.get("/api/checkpoints/report", format="json")
        entry = next(c for c in report["checkpoints"] if c["name"] == "fly_to_point")
        assert entry["state"] == "done" and entry["picture"].startswith("data:image/png;base64,")
    finally:
        second.stop()

    (folder / PROGRESS_FILE).write_text('{"format": 1, "records": ')  # cut short, as by a full disk
    third = start(tmp_path, "third")
    try:
        assert checkpoint(third, "fly_to_point")["state"] != "done"
        assert answer(third, "q1") == ""
        assert str(folder / PROGRESS_FILE) in third.log_tail(10**6)
        assert (folder / f"{PROGRESS_FILE}.corrupt").exists()
        # It serves as any lab: the next answer is saved in a good file again.
        assert (
            HTTP.put(
                f"{third.url}/api/checkpoints/answers/q2", json={"text": "again"}, timeout=10
            ).status_code
            == 200
        )
    finally:
        third.stop()
    assert '"again"' in (folder / PROGRESS_FILE).read_text()
