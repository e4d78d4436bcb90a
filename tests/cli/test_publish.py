"""publish.py: ``topic pub`` once, TIMES times at a rate, and at a rate until Ctrl-C."""

from __future__ import annotations

import json
from collections.abc import Callable
from typing import Any

import httpx
import pytest

from server.cli.client import LabClient
from server.cli.publish import publish_times

from .conftest import LiveServer, Result, Running


class FakeClock:
    """Time that moves only when the code under test sleeps."""

    def __init__(self) -> None:
        self.now = 100.0

    def sleep(self, seconds: float) -> None:
        self.now += seconds

    def monotonic(self) -> float:
        return self.now


def recording_client(clock: FakeClock, published: list[tuple[float, Any]]) -> LabClient:
    def handler(request: httpx.Request) -> httpx.Response:
        if request.method == "POST":
            published.append((clock.now, json.loads(request.content)))
            return httpx.Response(
                200, json={"topic": "/x", "type": "geometry_msgs/msg/Vector3", "subscribers": 0}
            )
        return httpx.Response(200, json={"x": 0.0, "y": 0.0, "z": 0.0})  # the type's default message

    return LabClient("http://lab.test", transport=httpx.MockTransport(handler))


def test_publish_times_exactly_times_messages_at_the_rate(capsys: pytest.CaptureFixture[str]) -> None:
    clock, published = FakeClock(), list[tuple[float, Any]]()
    body = {"topic": "/x", "msg": {"x": 5}, "type": "geometry_msgs/msg/Vector3"}
    assert publish_times(recording_client(clock, published), body, 3, 5.0, clock.sleep, clock.monotonic) == 0
    assert [round(t - 100.0, 9) for t, _ in published] == [0.0, 0.2, 0.4]
    assert all(b == body for _, b in published)
    assert capsys.readouterr().out == (
        "publisher: beginning loop\n"
        "publishing #1: geometry_msgs.msg.Vector3(x=5.0, y=0.0, z=0.0)\n\n"
        "publishing #2: geometry_msgs.msg.Vector3(x=5.0, y=0.0, z=0.0)\n\n"
        "publishing #3: geometry_msgs.msg.Vector3(x=5.0, y=0.0, z=0.0)\n\n"
    )


# -- against the live server ------------------------------------------------------------------
def test_pub_once_publishes_through_the_rest_node_and_echo_sees_it(
    live_server: LiveServer, ros2lab: Callable[..., Result], start: Callable[..., Running]
) -> None:
    echo = start("topic", "echo", "/abort_takeoff")
    echo.read_until(lambda line: line == "---")  # subscribed: the keyboard manager's false arrived
    result = ros2lab("topic", "pub", "-1", "/abort_takeoff", "std_msgs/msg/Bool", "{data: true}")
    assert result.code == 0, result.err
    assert result.out == "publisher: beginning loop\npublishing #1: std_msgs.msg.Bool(data=True)\n\n"
    assert "/_rest_api" in live_server.get("/api/topics/abort_takeoff")["publishers"]
    echo.read_until(lambda line: line == "data: true")
    live_server.post("/api/rocket/reset")  # un-abort the rocket for the other tests


def test_pub_rate_times_publishes_exactly_times_and_leaves_no_publisher(
    live_server: LiveServer, ros2lab: Callable[..., Result]
) -> None:
    result = ros2lab(
        "topic",
        "pub",
        "-r",
        "5",
        "-t",
        "3",
        "/cli_times",
        "geometry_msgs/msg/Vector3",
        "{x: 5.0, y: 5.0, z: 10.0}",
    )
    assert result.code == 0, result.err
    assert result.out.splitlines()[0] == "publisher: beginning loop"
    assert [line for line in result.out.splitlines() if line.startswith("publishing")] == [
        f"publishing #{n}: geometry_msgs.msg.Vector3(x=5.0, y=5.0, z=10.0)" for n in (1, 2, 3)
    ]
    assert live_server.get("/api/topics/cli_times")["publish_count"] == 3
    assert live_server.get("/api/publishers") == []


def test_pub_rate_runs_a_server_publisher_until_ctrl_c_then_deletes_it(
    live_server: LiveServer, start: Callable[..., Running]
) -> None:
    pub = start("topic", "pub", "-r", "20", "/cli_rate", "std_msgs/msg/Int64", "{data: 7}")
    pub.read_until(lambda line: line == "publishing #2: std_msgs.msg.Int64(data=7)")
    assert [p["topic"] for p in live_server.get("/api/publishers")] == ["/cli_rate"]
    code, err = pub.interrupt()
    assert (code, err) == (0, ""), err  # the whole of stderr, a traceback in full
    assert live_server.get("/api/publishers") == []


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["/abort_takeoff", "std_msgs/msg/Bool", "{dta: true}"], "has no field 'dta'"),
        (["/abort_takeoff", "std_msgs/msg/Int64", "{data: 1}"], "carries std_msgs/msg/Bool"),
        (["/abort_takeoff", "std_msgs/msg/Bool", "{data: 3}"], "expected a bool"),
        (["/abort_takeoff", "std_msgs/msg/Nope", "{}"], "unknown message type"),
        (["/abort_takeoff", "std_msgs/msg/Bool", "[true]"], "dictionary in YAML format"),
    ],
)
def test_pub_bad_input_exits_1_with_one_line_from_the_server(
    ros2lab: Callable[..., Result], args: list[str], message: str
) -> None:
    result = ros2lab("topic", "pub", "-1", *args)
    assert result.code == 1
    assert result.out == ""
    assert len(result.err.splitlines()) == 1
    assert message in result.err


def test_pub_at_a_rate_bad_message_starts_nothing(
    live_server: LiveServer, ros2lab: Callable[..., Result]
) -> None:
    result = ros2lab("topic", "pub", "-r", "10", "/abort_takeoff", "std_msgs/msg/Bool", "{data: 3}")
    assert result.code == 1
    assert "expected a bool" in result.err
    assert live_server.get("/api/publishers") == []
