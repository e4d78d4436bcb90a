"""/ws/topics/{name}: a live echo of one topic, like ``ros2 topic echo``, through the real app."""

from __future__ import annotations

import pytest
from labclient import LabClient, close_within, receive_json_within, wait_until

from api.errors import CloseCode

FRAME_KEYS = {"topic", "type", "msg", "received"}
FRAME_LIMIT = 16 * 1024  # Listening.max_ws_frame_bytes


def echo_nodes(lab: LabClient, topic: str) -> list[str]:
    return [n for n in lab.topic(topic)["subscribers"] if n.startswith("/_ws_echo_")]


def test_echo_countdown_streams_frames_in_order(counting_lab: LabClient) -> None:
    with counting_lab.http.websocket_connect("/ws/topics/countdown") as ws:
        first = receive_json_within(ws)
        second = receive_json_within(ws)

    for frame in (first, second):
        assert set(frame) == FRAME_KEYS
        assert frame["topic"] == "/countdown"
        assert frame["type"] == "std_msgs/msg/Int64"
        assert set(frame["msg"]) == {"data"}
        assert isinstance(frame["received"], float)
    assert second["msg"]["data"] == first["msg"]["data"] - 1
    assert second["received"] > first["received"]


def test_echo_type_param_new_topic_waits_then_streams_each_message(rocket_lab: LabClient) -> None:
    with rocket_lab.http.websocket_connect("/ws/topics/laps?type=std_msgs/msg/Int64") as ws:
        assert echo_nodes(rocket_lab, "/laps")  # the echo's own subscription made the topic
        results = [rocket_lab.publish("/laps", {"data": n}) for n in range(5)]
        frames = [receive_json_within(ws) for _ in range(5)]

    assert {r["subscribers"] for r in results} == {1}
    assert [f["msg"]["data"] for f in frames] == [0, 1, 2, 3, 4]
    assert {f["type"] for f in frames} == {"std_msgs/msg/Int64"}
    assert all(f["topic"] == "/laps" for f in frames)


def test_echo_throttled_queue_of_one_sends_only_the_newest(rocket_lab: LabClient) -> None:
    url = "/ws/topics/laps?type=std_msgs/msg/Int64&throttle_rate=1000&queue_length=1"
    with rocket_lab.http.websocket_connect(url) as ws:
        rocket_lab.publish("/laps", {"data": 0})
        assert receive_json_within(ws)["msg"] == {"data": 0}
        for n in range(1, 5):  # all inside the 1 s the echo now waits
            rocket_lab.publish("/laps", {"data": n})
        after_pause = receive_json_within(ws)

    assert after_pause["msg"] == {"data": 4}


def test_echo_throttled_without_a_queue_length_sends_the_newest_not_a_backlog(rocket_lab: LabClient) -> None:
    # 4 s between frames: the 29 publishes below fit in it even on a saturated machine (they took
    # over 1 s there, about 40 ms each, and the echo then rightly sent the newest of the first 25).
    url = "/ws/topics/laps?type=std_msgs/msg/Int64&throttle_rate=4000"
    with rocket_lab.http.websocket_connect(url) as ws:
        rocket_lab.publish("/laps", {"data": 0})
        assert receive_json_within(ws)["msg"] == {"data": 0}
        for n in range(1, 30):  # all inside the 4 s the echo now waits
            rocket_lab.publish("/laps", {"data": n})
        after_pause = receive_json_within(ws)
        rocket_lab.publish("/laps", {"data": 30})
        next_one = receive_json_within(ws)

    assert after_pause["msg"] == {"data": 29}
    assert next_one["msg"] == {"data": 30}  # not 1, 2, ...: nothing older waited behind the newest
    assert after_pause["dropped"] == 28  # 1 to 28, each replaced by a newer one while it waited


@pytest.mark.parametrize(
    "query",
    ["queue_length=0", "queue_length=1001", "queue_length=many", "throttle_rate=-1", "throttle_rate=60001"],
)
def test_echo_query_out_of_range_refused_naming_it(rocket_lab: LabClient, query: str) -> None:
    with rocket_lab.http.websocket_connect(f"/ws/topics/countdown?{query}") as ws:
        code, reason = close_within(ws)

    assert code == CloseCode.BAD_REQUEST
    assert query.split("=")[0] in reason
    assert echo_nodes(rocket_lab, "/countdown") == []


@pytest.mark.parametrize(
    ("path", "code", "named"),
    [
        ("nowhere", CloseCode.NOT_FOUND, "unknown topic /nowhere"),
        ("bad%20name", CloseCode.BAD_REQUEST, "invalid topic name"),
        ("countdown?type=std_msgs/msg/Bool", CloseCode.TYPE_CONFLICT, "std_msgs/msg/Int64"),
        ("laps?type=std_msgs/msg/Int65", CloseCode.BAD_REQUEST, "unknown message type"),
    ],
)
def test_echo_bad_topic_or_type_closes_with_named_code(
    rocket_lab: LabClient, path: str, code: CloseCode, named: str
) -> None:
    with rocket_lab.http.websocket_connect(f"/ws/topics/{path}") as ws:
        closed = close_within(ws)

    assert closed[0] == code
    assert named in closed[1]
    assert "/nowhere" not in rocket_lab.topic_names() and "/laps" not in rocket_lab.topic_names()
    assert rocket_lab.healthy()


@pytest.mark.parametrize(
    ("frame", "code"),
    [
        ({"text": "hello"}, CloseCode.UNSUPPORTED_DATA),
        ({"bytes": b"\x00\x01"}, CloseCode.UNSUPPORTED_DATA),
        ({"text": "x" * (FRAME_LIMIT + 1)}, CloseCode.MESSAGE_TOO_BIG),
    ],
    ids=["text", "binary", "oversized"],
)
def test_echo_client_sends_anything_closed_with_named_code(
    rocket_lab: LabClient, frame: dict[str, object], code: CloseCode
) -> None:
    with rocket_lab.http.websocket_connect("/ws/topics/countdown") as ws:
        ws.send({"type": "websocket.receive", **frame})
        closed = close_within(ws)

    assert closed[0] == code
    assert closed[1]  # a reason, for the person reading the browser's console
    wait_until(lambda: echo_nodes(rocket_lab, "/countdown") == [], "the echo's node to go")
    assert rocket_lab.healthy()
