"""A node process's faults stay in its process: a raise ends it (its launch says died, with its exit
code, and it leaves the node list), a loop that never returns leaves every other node running, and
no node process outlives the app."""

from __future__ import annotations

import os
import signal
from pathlib import Path
from typing import Any

from support.app import App

from .conftest import CRASHES, SPINS_FOREVER, make_workspace, node_entry, pid_alive

RESPAWNING = """
<launch>
  <node pkg="faults" exec="crasher.py" name="Crasher" respawn="true" respawn_delay="0.2"/>
</launch>
"""


def _countdown_count(app: App) -> int:
    return int(app.get("/api/topics/countdown")["publish_count"])


def _launch_of(app: App, launch_id: object) -> dict[str, Any] | None:
    return next((g for g in app.get("/api/launches") if g["id"] == launch_id), None)


def _died(app: App, launch_id: object) -> bool:
    group = _launch_of(app, launch_id)
    return group is not None and group["nodes"][0]["state"] == "died"


def _listed(app: App, name: str) -> bool:
    return node_entry(app, name) is not None or any(n["name"] == name for n in app.get("/api/graph")["nodes"])


def test_a_node_process_that_raises_dies_alone_and_leaves_the_node_list(tmp_path: Path) -> None:
    make_workspace(tmp_path, {"src/faults/crasher.py": CRASHES})
    app = App(tmp_path, "--launch", "rocket", "start_delay:=1", cwd=tmp_path)
    try:
        started = app.post("/api/run", {"package": "faults", "executable": "crasher.py"})
        assert started.status_code == 201, started.text
        launch_id = started.json()["id"]
        app.wait_for(lambda: node_entry(app, "/Crasher") is not None, "the crashing node in the graph")
        app.wait_for(lambda: _died(app, launch_id), "the crashing node's launch to say it died")
        # Its launch says so, with its exit code (what ``ros2lab launch`` reports once, as ros2
        # launch does); the graph and the node list no longer have it.
        (launched,) = _launch_of(app, launch_id)["nodes"]  # type: ignore[index]
        assert (launched["state"], launched["exit_code"]) == ("died", 1)
        app.wait_for(lambda: not _listed(app, "/Crasher"), "the dead node to leave the lists", 2.0)
        log = app.log_tail(50000)
        assert "RuntimeError: sensor unplugged" in log and "Traceback" in log  # its traceback, printed
        assert "process has died" in log
        before = _countdown_count(app)
        app.wait_for(lambda: _countdown_count(app) >= before + 2, "the countdown to keep going")
        assert all(n["state"] == "active" for n in app.get("/api/nodes"))
    finally:
        app.stop()


def test_a_crashed_node_run_again_and_stopped_is_in_no_list_5_s_after_stop(tmp_path: Path) -> None:
    """The tester's case: a run that crashed, then the corrected file run and stopped (the page's
    Run and Stop): nothing of either stays in the graph, alive or dead."""
    workspace = make_workspace(tmp_path, {"src/faults/crasher.py": CRASHES})
    app = App(tmp_path, "--launch", "rocket", cwd=tmp_path)
    try:
        crashed = app.post("/api/run", {"package": "faults", "executable": "crasher.py"})
        assert crashed.status_code == 201, crashed.text
        app.wait_for(lambda: _died(app, crashed.json()["id"]), "the first run to crash")
        (workspace / "src/faults/crasher.py").write_text(CRASHES.replace("raise RuntimeError", "print"))
        fixed = app.post("/api/run", {"package": "faults", "executable": "crasher.py"})
        assert fixed.status_code == 201, fixed.text
        app.wait_for(lambda: (node_entry(app, "/Crasher") or {}).get("state") == "active", "the fixed run")
        assert app.delete(f"/api/launches/{fixed.json()['id']}").status_code == 200
        app.wait_for(lambda: not _listed(app, "/Crasher"), "the stopped node to leave the lists", 5.0)
        assert not any(n["name"] == "/Crasher" for n in app.get("/api/nodes", hidden=True))
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
