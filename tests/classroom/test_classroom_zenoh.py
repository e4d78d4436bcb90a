"""A class server on Zenoh: each world joins the class's router in a ROS domain of its own, so a
student's node process (``ros2lab run`` with the student's token) joins their world only. The
server and the node run as processes of their own, on loopback, and are ended by their ids."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import httpx
import pytest
from support.app import App, end

CODE = "ZEN042"
TALKER = """
import rclpy
from rclpy.node import Node
from std_msgs.msg import Int64


class Talker(Node):
    def __init__(self):
        super().__init__('talker')
        self.pub = self.create_publisher(Int64, '/chatter', 10)
        self.count = 0
        self.create_timer(0.1, self.tick)

    def tick(self):
        self.count += 1
        self.pub.publish(Int64(data=self.count))


if __name__ == '__main__':
    rclpy.init()
    rclpy.spin(Talker())
"""


@pytest.fixture(scope="module")
def classroom(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[App, Path, dict[str, str]]]:
    root = tmp_path_factory.mktemp("classroom_zenoh")
    talker = root / "workspace" / "src" / "demo" / "demo" / "talker.py"
    talker.parent.mkdir(parents=True)
    talker.write_text(TALKER.lstrip())
    app = App(root, "--classroom", "--class-code", CODE, "--launch", "rocket", "start_delay:=600", cwd=root)
    try:
        tokens = {}
        for name in ("Ada", "Bob"):
            reply = httpx.post(f"{app.url}/api/classroom/join", json={"name": name, "code": CODE}, timeout=30)
            assert reply.status_code == 201, reply.text
            tokens[reply.json()["world"]] = reply.json()["token"]
        yield app, root, tokens
    finally:
        app.stop()


def get(app: App, token: str, path: str) -> httpx.Response:
    return httpx.get(app.url + path, headers={"Authorization": f"Bearer {token}"}, timeout=5.0)


def test_each_world_has_a_ros_domain_of_its_own(classroom: tuple[App, Path, dict[str, str]]) -> None:
    app, _root, tokens = classroom
    domains = {w: get(app, t, "/api/health").json()["zenoh"]["domain_id"] for w, t in tokens.items()}
    assert domains == {"ada": 1, "bob": 2}


def test_a_students_node_process_joins_their_world_only(classroom: tuple[App, Path, dict[str, str]]) -> None:
    app, root, tokens = classroom
    env = {**os.environ, "ROS2LAB_TOKEN": tokens["ada"]}
    env.pop("ROS_DOMAIN_ID", None)
    run = subprocess.Popen(
        [sys.executable, "-m", "server", "--url", app.url, "run", "demo", "talker.py"],
        cwd=root, env=env, text=True, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
    )  # fmt: skip
    try:

        def ada_hears() -> bool:
            rate: dict[str, Any] = get(app, tokens["ada"], "/api/hz/chatter?window=5").json()
            return rate.get("window") == 5

        app.wait_for(ada_hears, "Ada's world hearing her talker's /chatter")
        nodes = {n["name"]: n for n in get(app, tokens["ada"], "/api/nodes").json()}
        assert nodes["/talker"]["location"] != "app"  # another process, on the class's Zenoh graph
        assert get(app, tokens["bob"], "/api/topics/chatter").status_code == 404
        assert "/talker" not in {n["name"] for n in get(app, tokens["bob"], "/api/nodes").json()}
    finally:
        run.send_signal(signal.SIGINT)
        try:
            run.communicate(timeout=15)
        except subprocess.TimeoutExpired:
            end(run)
    app.wait_for(lambda: "/talker" not in {n["name"] for n in get(app, tokens["ada"], "/api/nodes").json()},
                 "the talker gone from Ada's world once it stopped")  # fmt: skip
