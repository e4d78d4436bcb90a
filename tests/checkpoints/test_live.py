"""Checkpoints 1 and 3 as a student meets them: ``python -m server`` in a subprocess (its Zenoh
router on loopback), a temp workspace with the student's nodes run as their own processes through
``POST /api/run`` and ``/api/launch``, keys through ``/ws/keys``; and ``ros2lab report verify``.
One server for the module."""

from __future__ import annotations

import json
import subprocess
import textwrap
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from support.app import App
from support.forked_cli import cli_command
from support.http import HTTP
from support.wait import wait_until
from websockets.sync.client import ClientConnection, connect

ABORT_ON_A = """
import rclpy
from rclpy.node import Node
from keyboard_msgs.msg import Key
from std_msgs.msg import Bool


class StudentAbort(Node):
    def __init__(self):
        super().__init__('StudentAbort')
        self.pub = self.create_publisher(Bool, '/abort_takeoff', 1)
        self.create_subscription(Key, '/keydown', self.on_key, 1)

    def on_key(self, msg):
        if msg.code == Key.KEY_A:
            self.pub.publish(Bool(data=True))


if __name__ == '__main__':
    rclpy.init()
    rclpy.spin(StudentAbort())
"""

ARROW_KEYS = """
import rclpy
from rclpy.node import Node
from keyboard_msgs.msg import Key
from geometry_msgs.msg import Vector3

STEPS = {Key.KEY_RIGHT: (1.5, 0.0), Key.KEY_LEFT: (-1.5, 0.0), Key.KEY_UP: (0.0, 1.5), Key.KEY_DOWN: (0.0, -1.5)}


class ArrowKeys(Node):
    def __init__(self):
        super().__init__('ArrowKeys')
        self.pos = Vector3(x=0.0, y=0.0, z=3.0)
        self.pub = self.create_publisher(Vector3, '/uav/input/position', 1)
        self.create_subscription(Key, '/keydown', self.on_key, 10)

    def on_key(self, msg):
        if msg.code in STEPS:
            dx, dy = STEPS[msg.code]
            self.pos.x += dx
            self.pos.y += dy
            self.pub.publish(self.pos)


if __name__ == '__main__':
    rclpy.init()
    rclpy.spin(ArrowKeys())
"""

FLY_KEYS = """<?xml version="1.0"?>
<launch>
  <include file="$(find-pkg-share flightcontroller)/launch/position.launch">
    <arg name="simple" value="true"/>
  </include>
  <node pkg="simple_sim" exec="simple_sim_node"/>
  <node pkg="keyboard" exec="keyboard" name="drone_keyboard"/>
  <node pkg="drone_keys" exec="arrow_keys" name="ArrowKeys"/>
</launch>
"""

# The rocket without its keyboard manager: the tests choose which one runs. Named as the lab's, so
# that POST /api/rocket/reset restarts its nodes.
ROCKET = """<?xml version="1.0"?>
<launch>
  <node pkg="rocketship" exec="rocket_engine.py" name="RocketEngineNode"/>
  <node pkg="rocketship" exec="main_controller" name="MainControllerNode"/>
  <node pkg="rocketship" exec="countdown" name="CountDownNode">
    <param name="start_delay_s" value="2.0"/>
  </node>
  <node pkg="keyboard" exec="keyboard" name="keyboard"/>
</launch>
"""


@pytest.fixture(scope="module")
def app(tmp_path_factory: pytest.TempPathFactory) -> Iterator[App]:
    root = tmp_path_factory.mktemp("checkpoints_live")
    files = {
        "workspace/src/rocket_keys/abort_on_a.py": ABORT_ON_A,
        "workspace/src/drone_keys/arrow_keys.py": ARROW_KEYS,
        "workspace/src/drone_keys/launch/fly_keys.launch": FLY_KEYS,
        "base/rocket.launch": ROCKET,
    }
    for rel, text in files.items():
        (root / rel).parent.mkdir(parents=True, exist_ok=True)
        (root / rel).write_text(textwrap.dedent(text).lstrip())
    server = App(root, "--launch", str(root / "base" / "rocket.launch"), "--no-foxglove", cwd=root)
    try:
        yield server
    finally:
        server.stop()


@pytest.fixture(scope="module")
def keys(app: App) -> Iterator[ClientConnection]:
    with connect(f"ws://127.0.0.1:{app.port}/ws/keys") as ws:
        yield ws


def press(keys: ClientConnection, key: str) -> None:
    keys.send(json.dumps({"type": "keydown", "key": key}))
    keys.send(json.dumps({"type": "keyup", "key": key}))


def wait_for(app: App, condition: Any, what: str, timeout_s: float = 20.0) -> None:
    """Until ``condition`` holds; on failure, the checkpoints as they stand and the app's log."""
    wait_until(
        condition,
        what,
        timeout_s,
        poll_s=0.1,
        detail=lambda: (
            json.dumps(app.get("/api/checkpoints")["checkpoints"], indent=1)[:3000] + app.log_tail(1500)
        ),
    )


def check(app: App, name: str) -> dict[str, Any]:
    return next(c for c in app.get("/api/checkpoints")["checkpoints"] if c["name"] == name)


def latest(app: App, topic: str) -> Any:
    return app.get(f"/api/topics/{topic}")["latest"]


def restart_countdown(app: App) -> None:
    """Reset the rocket and wait for its new countdown to be under way (10 s after a 2 s delay)."""
    before = app.get("/api/topics/countdown")["publish_count"]
    assert app.post("/api/rocket/reset", {}).status_code == 200

    def counting() -> bool:
        topic = app.get("/api/topics/countdown")
        return topic["publish_count"] >= before + 2 and 3 <= topic["latest"]["data"] <= 9

    wait_for(app, counting, "the new countdown under way", 30.0)


def abort_seen(app: App) -> bool:
    return bool((latest(app, "abort_takeoff") or {}).get("data"))


def test_checkpoint_1_not_with_the_labs_manager_nor_by_hand_nor_after_lift_off_but_with_the_students(
    app: App, keys: ClientConnection
) -> None:
    # The lab's own keyboard manager, in the app: it aborts, but it is not the student's.
    lab_run = app.post("/api/run", {"package": "rocketship", "executable": "keyboard_manager.py"}).json()
    restart_countdown(app)
    wait_for(
        app,
        lambda: (
            press(keys, "a"),
            "not from a keyboard manager of your workspace" in check(app, "keyboard_abort")["progress"],
        )[1],
        "the check to name the lab's manager",
    )
    assert abort_seen(app)
    assert check(app, "keyboard_abort")["state"] != "done"
    assert app.delete(f"/api/launches/{lab_run['id']}").status_code == 200

    # By hand, right after an "a".
    restart_countdown(app)
    press(keys, "a")
    app.post("/api/publish", {"topic": "/abort_takeoff", "msg": {"data": True}, "type": "std_msgs/msg/Bool"})
    wait_for(
        app,
        lambda: "/_rest_api" in check(app, "keyboard_abort")["progress"],
        "the check to name the REST abort",
    )
    assert check(app, "keyboard_abort")["state"] != "done"

    # The student's process, but after lift-off (the REST abort above stopped this countdown's).
    assert (
        app.post(
            "/api/run", {"package": "rocket_keys", "executable": "abort_on_a", "name": "StudentAbort"}
        ).status_code
        == 201
    )
    restart_countdown(app)
    wait_for(
        app,
        lambda: any(n["name"] == "/StudentAbort" for n in app.get("/api/nodes")),
        "the student's node",
        30.0,
    )
    wait_for(app, lambda: ((latest(app, "cmd_vel") or {}).get("data") or 0) > 0, "lift-off", 30.0)
    wait_for(
        app,
        lambda: (press(keys, "a"), "lifted off" in check(app, "keyboard_abort")["progress"])[1],
        "the student's abort after lift-off seen",
    )
    assert check(app, "keyboard_abort")["state"] != "done"

    # The student's process during the countdown: met.
    restart_countdown(app)
    wait_for(
        app,
        lambda: (press(keys, "a"), check(app, "keyboard_abort")["state"] == "done")[1],
        "checkpoint 1 done",
        20.0,
    )
    evidence = check(app, "keyboard_abort")["evidence"]
    assert evidence["student_node"] == "/StudentAbort" and evidence["student_process"].startswith("process ")
    assert "/StudentAbort" in {n["name"] for n in evidence["graph"]["nodes"]}
    assert {"source": "/StudentAbort", "target": "/abort_takeoff", "kind": "publish"} in evidence["graph"][
        "edges"
    ]


def fly_with_arrows(app: App, keys: ClientConnection, name: str) -> None:
    for key in ("ArrowRight", "ArrowUp", "ArrowRight", "ArrowUp"):
        press(keys, key)


def test_checkpoint_3_not_with_the_labs_fly_launch_but_with_the_workspaces(
    app: App, keys: ClientConnection
) -> None:
    lab_fly = app.post(
        "/api/launch",
        {
            "file": "fly.launch",
            "package": "flightcontroller",
            "args": {"simple": "true", "keyboard": "false"},
        },
    )
    assert lab_fly.status_code == 201, lab_fly.text
    wait_for(
        app,
        lambda: "not a file of your workspace" in check(app, "launch_and_keys")["progress"],
        "the check to name the lab's launch",
    )
    assert app.delete(f"/api/launches/{lab_fly.json()['id']}").status_code == 200

    mine = app.post("/api/launch", {"file": "fly_keys.launch", "package": "drone_keys"})
    assert mine.status_code == 201, mine.text
    wait_for(
        app, lambda: any(n["name"] == "/ArrowKeys" for n in app.get("/api/nodes")), "the student's node", 30.0
    )
    wait_for(app, lambda: latest(app, "uav/sensors/gps") is not None, "the drone's GPS", 30.0)

    def moved() -> bool:
        state = check(app, "launch_and_keys")
        if state["state"] == "done":
            return True
        if "0 setpoints" in state["progress"]:  # the node's route to /keydown may be new: press again
            fly_with_arrows(app, keys, "again")
        return False

    fly_with_arrows(app, keys, "first")
    wait_for(app, moved, "checkpoint 3 done", 60.0)
    evidence = check(app, "launch_and_keys")["evidence"]
    assert evidence["launch_file"].endswith("fly_keys.launch") and "arrow_keys" in evidence["launch_text"]
    assert min(evidence["moved_m"]) >= 2.0
    assert any(n["student"] and n["exec"] == "arrow_keys" for n in evidence["nodes"])


def ros2lab(app: App, *args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(cli_command(*args, "--url", app.url), capture_output=True, text=True, timeout=60)


def test_ros2lab_report_verify_exits_0_when_valid_and_1_when_edited(app: App, tmp_path: Path) -> None:
    report = HTTP.get(app.url + "/api/checkpoints/report", params={"format": "html"}, timeout=10).content
    good = tmp_path / "report.html"
    good.write_bytes(report)
    result = ros2lab(app, "report", "verify", str(good))
    assert result.returncode == 0 and "valid" in result.stdout, result.stdout + result.stderr

    edited = tmp_path / "edited.html"
    edited.write_bytes(report.replace(b"done", b"d0ne", 1))
    result = ros2lab(app, "report", "verify", str(edited))
    assert result.returncode == 1 and "edited" in result.stdout
