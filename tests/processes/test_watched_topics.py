"""A topic only a node process publishes, and nothing in the app subscribes to, is seen by the app's
tools as a topic of its own is: ``GET /api/topics/{name}`` starts listening on first use (as ``ros2
topic echo`` does), says so, and then carries the latest message; ``/api/hz`` likewise; the echo
WebSocket needs no ``?type=``. The node is a real process the app starts (``POST /api/run``)."""

from __future__ import annotations

import json
from collections.abc import Iterator
from typing import Any

import pytest
from support.app import App
from support.http import HTTP
from websockets.sync.client import connect

from .conftest import make_workspace, node_entry

TALKER = """
import rclpy
from rclpy.node import Node
from std_msgs.msg import Int64


class Talker(Node):
    def __init__(self):
        super().__init__('watched_talker')
        self.pubs = [self.create_publisher(Int64, f'/watched_{n}', 10) for n in ('latest', 'hz', 'echo')]
        self.count = 0
        self.create_timer(0.1, self.tick)

    def tick(self):
        self.count += 1
        for pub in self.pubs:
            pub.publish(Int64(data=self.count))


if __name__ == '__main__':
    rclpy.init()
    try:
        rclpy.spin(Talker())
    except KeyboardInterrupt:
        pass
    finally:
        rclpy.try_shutdown()
"""


@pytest.fixture(scope="module")
def lab(tmp_path_factory: pytest.TempPathFactory) -> Iterator[App]:
    """The rocket (nothing of it touches /watched_*) and the talker as a process of its own."""
    root = tmp_path_factory.mktemp("watched")
    make_workspace(root, {"src/watched/talker.py": TALKER})
    app = App(root, "--launch", "rocket", "start_delay:=3600", cwd=root)
    try:
        started = app.post("/api/run", {"package": "watched", "executable": "talker.py"})
        assert started.status_code == 201, started.text
        app.wait_for(lambda: node_entry(app, "/watched_talker") is not None, "the talker in the graph")
        app.wait_for(
            lambda: (
                {"/watched_latest", "/watched_hz", "/watched_echo"}
                <= {t["name"] for t in app.get("/api/topics")}
            ),
            "the talker's topics in the graph",
        )
        yield app
    finally:
        app.stop()


def test_topic_info_of_a_topic_only_a_process_publishes_starts_a_watch_then_shows_its_latest(
    lab: App,
) -> None:
    first = lab.get("/api/topics/watched_latest")
    assert first["watch"] == "started"
    assert first["latest"] is None  # nothing here listened before this request
    assert first["publishers"] == ["/watched_talker"] and first["subscribers"] == []
    seen: dict[str, Any] = {}

    def has_latest() -> bool:
        seen.update(lab.get("/api/topics/watched_latest"))
        return seen["latest"] is not None

    lab.wait_for(has_latest, "the talker's latest message through GET /api/topics", 10.0)
    assert seen["watch"] == "running"
    assert isinstance(seen["latest"]["data"], int) and seen["latest"]["data"] > 0
    assert seen["publish_count"] >= 1 and seen["latest_time"] is not None
    # The app's own listener is not one of the topic's subscriptions (topic info counts the same).
    assert seen["subscribers"] == [] and all(e["kind"] == "publisher" for e in seen["endpoints"])
    listed = next(t for t in lab.get("/api/topics") if t["name"] == "/watched_latest")
    assert listed["subscribers"] == []
    # It keeps up: a later message replaces the one seen.
    before = seen["latest"]["data"]
    lab.wait_for(
        lambda: lab.get("/api/topics/watched_latest")["latest"]["data"] > before, "a newer message", 10.0
    )


def test_topic_the_app_subscribes_itself_needs_no_watch(lab: App) -> None:
    """/countdown's subscriber is the rocket's controller, in the app: every message reaches it."""
    info = lab.get("/api/topics/countdown")
    assert info["watch"] is None
    assert "/MainControllerNode" in info["subscribers"]
    assert lab.get("/api/hz/countdown")["watch"] is None


def test_hz_of_a_topic_only_a_process_publishes_starts_a_watch_then_measures(lab: App) -> None:
    first = lab.get("/api/hz/watched_hz", window=5)
    assert first["watch"] == "started" and first["window"] == 0 and first["rate_hz"] is None
    seen: dict[str, Any] = {}

    def measured() -> bool:
        seen.update(lab.get("/api/hz/watched_hz", window=5))
        return bool(seen["window"] == 5)

    lab.wait_for(measured, "five periods of the talker's topic", 10.0)
    assert seen["watch"] == "running" and seen["rate_hz"] is not None and seen["rate_hz"] > 0


def test_unknown_topic_is_404_and_starts_no_watch(lab: App) -> None:
    for path in ("/api/topics/nobody_publishes_this", "/api/hz/nobody_publishes_this"):
        response = HTTP.get(lab.url + path, timeout=5.0)
        assert response.status_code == 404, response.text
        assert "/nobody_publishes_this" in response.text
    hidden = lab.get("/api/graph", hidden="true")
    assert "/nobody_publishes_this" not in {t["name"] for t in hidden["topics"]}


def test_echo_socket_without_a_type_carries_a_topic_only_a_process_publishes(lab: App) -> None:
    with connect(f"ws://127.0.0.1:{lab.port}/ws/topics/watched_echo", open_timeout=10.0) as ws:
        frame = json.loads(ws.recv(timeout=10.0))
        later = json.loads(ws.recv(timeout=10.0))
    assert frame["topic"] == "/watched_echo" and frame["type"] == "std_msgs/msg/Int64"
    assert later["msg"]["data"] > frame["msg"]["data"] > 0
