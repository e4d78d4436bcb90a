"""The handout's own node files, verbatim but for their TODOs (examples/workspace), each run as its
own process by the app's launch files, as a student runs them."""

from __future__ import annotations

import re
from collections.abc import Iterator
from pathlib import Path

import pytest
from support.app import App

from .conftest import RATE_NODE, Keys, make_workspace, node_entry, pid_alive


@pytest.fixture
def rocket(tmp_path: Path) -> Iterator[App]:
    make_workspace(tmp_path)
    app = App(tmp_path, "--launch", "rocket", "start_delay:=6", cwd=tmp_path)
    try:
        yield app
    finally:
        app.stop()


def test_part1_keyboard_manager_process_aborts_the_rocket_on_a(rocket: App, keys_for: type[Keys]) -> None:
    rocket.wait_for(
        lambda: node_entry(rocket, "/KeyboardManager") is not None, "the student's node in the graph"
    )
    entry = node_entry(rocket, "/KeyboardManager")
    assert entry is not None and str(entry["location"]).startswith("process ")
    pid = int(str(entry["location"]).split()[1])
    keys = keys_for(rocket)

    def aborted() -> bool:
        latest = rocket.get("/api/topics/abort_takeoff")["latest"]
        if not (latest and latest["data"]):
            keys.press("a")  # again, until the new process's subscription has its route
            return False
        return True

    rocket.wait_for(aborted, "/abort_takeoff to turn true")
    # Its print(), labelled with its executable as ros2 launch labels a process's lines.
    assert re.search(
        r"^\[keyboard_manager\.py-\d+\] a key was pressed!$", rocket.log_tail(50000), re.MULTILINE
    )
    rocket.wait_for(
        lambda: (rocket.get("/api/topics/countdown")["latest"] or {}).get("data") == 0,
        "the countdown's end",
        30.0,
    )
    assert rocket.get("/api/topics/cmd_vel")["publish_count"] == 0, "the rocket lifted off after the abort"
    rocket.stop()
    assert not pid_alive(pid), "the node process outlived the app"


def test_part2_drone_keyboard_manager_moves_the_setpoint_a_metre_per_press(
    tmp_path: Path, keys_for: type[Keys]
) -> None:
    make_workspace(tmp_path)
    app = App(tmp_path, "--launch", "fly", cwd=tmp_path)
    try:
        # The file sleeps 10 s in its constructor (for real, in its own process), then publishes.
        def from_student() -> bool:
            topic = app.get("/api/topics/uav/input/position")
            return (
                any(
                    e["node"] == "/keyboard_manager_node" and e["location"].startswith("process")
                    for e in topic["endpoints"]
                    if e["kind"] == "publisher"
                )
                and topic["latest"] is not None
            )

        app.wait_for(from_student, "the student's node to publish after its sleep", 30.0)
        keys = keys_for(app)

        def setpoint() -> tuple[float, float, float]:
            latest = app.get("/api/topics/uav/input/position")["latest"]
            return latest["x"], latest["y"], latest["z"]

        app.wait_for(lambda: setpoint() == (0.0, 0.0, 3.0), "the student's first setpoint")
        for key, expected in [
            ("ArrowRight", (1.0, 0.0, 3.0)),
            ("ArrowRight", (2.0, 0.0, 3.0)),
            ("ArrowUp", (2.0, 1.0, 3.0)),
            ("ArrowLeft", (1.0, 1.0, 3.0)),
        ]:
            keys.press(key)
            app.wait_for(lambda e=expected: setpoint() == e, f"the setpoint at {expected}", 5.0)
    finally:
        app.stop()


@pytest.mark.timing
def test_method1_rate_loop_in_main_publishes_at_5_hz(tmp_path: Path) -> None:
    make_workspace(tmp_path, {"src/rates/rate_node.py": RATE_NODE})
    app = App(tmp_path, "--launch", "rocket", cwd=tmp_path)
    try:
        started = app.post("/api/run", {"package": "rates", "executable": "rate_node.py"})
        assert started.status_code == 201, started.text
        app.wait_for(lambda: node_entry(app, "/RateNode") is not None, "the rate node in the graph")
        app.wait_for(lambda: any(t["name"] == "/rate_demo" for t in app.get("/api/topics")), "its topic")

        def measured() -> bool:
            hz = app.get("/api/hz/rate_demo", window=20)
            return hz["window"] >= 20

        app.wait_for(measured, "20 periods of /rate_demo", 15.0)
        hz = app.get("/api/hz/rate_demo", window=20)
        assert hz["rate_hz"] == pytest.approx(5.0, rel=0.10)
    finally:
        app.stop()
