"""A node process's faults stay in its process: a raise ends it (listed as died, with its exit code),
a loop that never returns leaves every other node running, and no node process outlives the app."""

from __future__ import annotations

import os
import signal
from pathlib import Path

from support.app import App

from .conftest import CRASHES, SPINS_FOREVER, make_workspace, node_entry, pid_alive

RESPAWNING = """
<launch>
  <node pkg="faults" exec="crasher.py" name="Crasher" respawn="true" respawn_delay="0.2"/>
</launch>
"""


def _countdown_count(app: App) -> int:
    return int(app.get("/api/topics/countdown")["publish_count"])


def test_a_node_process_that_raises_dies_alone_listed_as_died_with_its_exit_code(tmp_path: Path) -> None:
    make_workspace(tmp_path, {"src/faults/crasher.py": CRASHES})
    app = App(tmp_path, "--launch", "rocket", "start_delay:=1", cwd=tmp_path)
    try:
        started = app.post("/api/run", {"package": "faults", "executable": "crasher.py"})
        assert started.status_code == 201, started.text

        def died() -> bool:
            entry = node_entry(app, "/Crasher")
            return entry is not None and entry["state"] == "died"

        app.wait_for(died, "the crashing node to be listed as died")
        entry = node_entry(app, "/Crasher")
        assert entry is not None and entry["exit_code"] == 1 and str(entry["location"]).startswith("process ")
        # Its launch says so too (what ``ros2lab launch`` reports once, as ros2 launch does).
        (launched,) = next(g for g in app.get("/api/launches") if g["id"] == started.json()["id"])["nodes"]
        assert (launched["state"], launched["exit_code"]) == ("died", 1)
        graph = app.get("/api/graph")
        assert {"name": "/Crasher", "state": "died"}.items() <= next(
            n for n in graph["nodes"] if n["name"] == "/Crasher"
        ).items()
        log = app.log_tail(50000)
        assert "RuntimeError: sensor unplugged" in log and "Traceback" in log  # its traceback, printed
        assert "process has died" in log
        before = _countdown_count(app)
        app.wait_for(lambda: _countdown_count(app) >= before + 2, "the countdown to keep going")
        assert all(n["state"] == "active" for n in app.get("/api/nodes") if n["name"] != "/Crasher")
    finally:
        app.stop()


def test_a_node_process_that_never_returns_from_a_callback_leaves_the_rest_running(tmp_path: Path) -> None:
    make_workspace(tmp_path, {"src/faults/busy.py": SPINS_FOREVER})
    # The countdown (10 s from 8 s after start) runs while the busy node, whose process may take
    # seconds to start on a loaded machine, sits in its callback.
    app = App(tmp_path, "--launch", "rocket", "start_delay:=8", cwd=tmp_path)
    try:
        started = app.post("/api/run", {"package": "faults", "executable": "busy.py"})
        assert started.status_code == 201
        app.wait_for(lambda: node_entry(app, "/Busy") is not None, "the busy node in the graph")
        app.wait_for(
            lambda: "into the endless callback" in app.log_tail(50000),
            "the busy node inside its endless callback",
        )
        before = _countdown_count(app)
        app.wait_for(lambda: _countdown_count(app) >= before + 3, "the countdown to go on meanwhile")
        assert app.get("/api/health")["status"] == "ok"
        entry = node_entry(app, "/Busy")
        assert entry is not None and entry["state"] == "active"  # alive, just busy: as ros2 node list says
        pid = int(str(entry["location"]).split()[1])
        stopped = app.delete(f"/api/launches/{started.json()['id']}")
        assert stopped.status_code == 200
        app.wait_for(lambda: not pid_alive(pid), "Ctrl-C to end the busy process", 10.0)
    finally:
        app.stop()


def test_a_respawning_node_process_backs_off_as_the_node_list_shows(tmp_path: Path) -> None:
    make_workspace(tmp_path, {"src/faults/crasher.py": CRASHES, "src/faults/launch/crash.launch": RESPAWNING})
    app = App(tmp_path, "--launch", "rocket", cwd=tmp_path)
    try:
        answer = app.post("/api/launch", {"package": "faults", "file": "crash.launch"})
        assert answer.status_code == 201, answer.text

        def respawned_twice() -> bool:
            entry = node_entry(app, "/Crasher")
            return bool(entry and entry.get("respawn") and entry["respawn"]["respawns"] >= 2)  # type: ignore[index]

        app.wait_for(respawned_twice, "two respawns", 30.0)
        assert app.log_tail(50000).count("process started with pid") >= 3
    finally:
        app.stop()


def test_killing_the_app_ends_its_node_processes(tmp_path: Path) -> None:
    make_workspace(tmp_path)
    app = App(tmp_path, "--launch", "rocket", cwd=tmp_path)
    try:
        app.wait_for(lambda: node_entry(app, "/KeyboardManager") is not None, "the student's node process")
        entry = node_entry(app, "/KeyboardManager")
        assert entry is not None
        pid = int(str(entry["location"]).split()[1])
        assert pid_alive(pid)
        os.kill(app.proc.pid, signal.SIGKILL)
        app.proc.wait(timeout=10)
        app.wait_for(lambda: not pid_alive(pid), "the node process to end with the app", 10.0)
    finally:
        app.stop()
