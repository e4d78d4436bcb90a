"""The rosbridge protocol without a socket: a session on a bus stepped by hand, its frames
pulled by hand. Bounded queues, throttling, merging, names, services and status gating."""

from __future__ import annotations

import asyncio
import json
from collections.abc import Iterator
from typing import Any

import pytest

from node_runtime.bus import Bus, Executor, Node
from node_runtime.msgs import Bool, Int64, Vector3, get_service_type
from server.services.bridges.rosbridge import DEFAULT_QUEUE, MAX_TOPICS, RosbridgeSession


@pytest.fixture
def loop() -> Iterator[asyncio.AbstractEventLoop]:
    loop = asyncio.new_event_loop()
    yield loop
    loop.close()


@pytest.fixture
def talker(bus: Bus) -> Node:
    with bus.activate():
        return Node("talker")


def drain(session: RosbridgeSession, now_s: float = 0.0) -> list[dict[str, Any]]:
    frames = []
    while (frame := session.next_frame(now_s)[0]) is not None:
        frames.append(json.loads(frame))
    return frames


def test_slow_client_keeps_only_the_newest_queue_length_messages(
    bus: Bus, executor: Executor, loop: asyncio.AbstractEventLoop, talker: Node
) -> None:
    pub = talker.create_publisher(Int64, "/count", 10)
    session = RosbridgeSession(bus, loop)
    session.handle({"op": "subscribe", "id": "s", "topic": "/count", "queue_length": 5})
    for i in range(50):
        pub.publish(Int64(data=i))
        executor.spin_some()
    frames = drain(session)
    assert [f["msg"]["data"] for f in frames] == [45, 46, 47, 48, 49]
    assert session.stats.dropped == 45
    assert all(f == {"op": "publish", "topic": "/count", "msg": f["msg"]} for f in frames)


def test_default_queue_is_bounded_too(
    bus: Bus, executor: Executor, loop: asyncio.AbstractEventLoop, talker: Node
) -> None:
    pub = talker.create_publisher(Int64, "/count", 10)
    session = RosbridgeSession(bus, loop)
    session.handle({"op": "subscribe", "topic": "count", "queue_length": 0})  # the clients' default
    for i in range(DEFAULT_QUEUE * 3):
        pub.publish(Int64(data=i))
        executor.spin_some()
    frames = drain(session)
    assert len(frames) == DEFAULT_QUEUE and frames[-1]["msg"]["data"] == DEFAULT_QUEUE * 3 - 1
    assert frames[0]["topic"] == "count"  # under the client's own spelling, as it dispatches on it


def test_throttle_rate_spaces_frames_and_says_how_long_to_wait(
    bus: Bus, executor: Executor, loop: asyncio.AbstractEventLoop, talker: Node
) -> None:
    pub = talker.create_publisher(Int64, "/count", 10)
    session = RosbridgeSession(bus, loop)
    session.handle({"op": "subscribe", "topic": "/count", "throttle_rate": 100, "queue_length": 1})
    for i in range(3):
        pub.publish(Int64(data=i))
        executor.spin_some()
    first, _ = session.next_frame(10.0)
    assert first is not None and json.loads(first)["msg"]["data"] == 2  # queue_length 1: the newest
    pub.publish(Int64(data=3))
    executor.spin_some()
    frame, wait = session.next_frame(10.05)
    assert frame is None and wait == pytest.approx(0.05)
    frame, _ = session.next_frame(10.1)
    assert frame is not None and json.loads(frame)["msg"]["data"] == 3


def test_throttle_with_the_default_queue_sends_the_newest_not_a_backlog(
    bus: Bus, executor: Executor, loop: asyncio.AbstractEventLoop, talker: Node
) -> None:
    pub = talker.create_publisher(Int64, "/count", 10)
    session = RosbridgeSession(bus, loop)
    session.handle({"op": "subscribe", "topic": "/count", "throttle_rate": 100, "queue_length": 0})
    for i in range(10):
        pub.publish(Int64(data=i))
        executor.spin_some()
    first, _ = session.next_frame(10.0)
    assert first is not None and json.loads(first)["msg"]["data"] == 9
    for i in range(10, 20):  # a 100 Hz topic during the 100 ms throttle
        pub.publish(Int64(data=i))
        executor.spin_some()
    second, _ = session.next_frame(10.1)
    assert second is not None and json.loads(second)["msg"]["data"] == 19
    assert session.next_frame(10.2) == (None, None)  # nothing older was kept behind it


def test_two_subscribe_ids_share_one_stream_until_both_unsubscribe(
    bus: Bus, executor: Executor, loop: asyncio.AbstractEventLoop, talker: Node
) -> None:
    pub = talker.create_publisher(Bool, "/flag", 10)
    session = RosbridgeSession(bus, loop)
    session.handle({"op": "subscribe", "id": "a", "topic": "/flag"})
    session.handle({"op": "subscribe", "id": "b", "topic": "/flag", "type": "std_msgs/Bool"})
    pub.publish(Bool(data=True))
    executor.spin_some()
    assert len(drain(session)) == 1
    session.handle({"op": "unsubscribe", "id": "a", "topic": "/flag"})
    assert pub.get_subscription_count() == 1
    session.handle({"op": "unsubscribe", "id": "b", "topic": "/flag"})
    assert pub.get_subscription_count() == 0


def test_advertise_and_publish_with_either_type_spelling(
    bus: Bus, executor: Executor, loop: asyncio.AbstractEventLoop
) -> None:
    got: list[bool] = []
    with bus.activate():
        Node("listener").create_subscription(Bool, "/flag", lambda m: got.append(m.data), 10)
    session = RosbridgeSession(bus, loop)
    session.handle({"op": "advertise", "topic": "flag", "type": "std_msgs/msg/Bool"})
    session.handle({"op": "publish", "topic": "flag", "msg": {"data": True}})
    session.handle({"op": "advertise", "topic": "/flag", "type": "std_msgs/Bool"})
    session.handle({"op": "publish", "topic": "/flag", "msg": {"data": False}})
    executor.spin_some()
    assert got == [True, False] and session.stats.refused == 0
    session.handle({"op": "unadvertise", "topic": "flag"})
    assert bus.topics["/flag"].publishers == []


@pytest.mark.parametrize(
    "request_",
    [
        {"op": "publish", "topic": "/nowhere", "msg": {}},  # not advertised and no such topic
        {"op": "publish", "topic": "/uav/input/position", "msg": {"x": float("nan")}},
        {"op": "advertise", "topic": "/flag", "type": "std_msgs/Int64"},  # the topic is a Bool
        {"op": "advertise", "topic": "/x", "type": "no_pkg/Nothing"},
        {"op": "subscribe", "topic": "/not_yet"},  # no type to create it with
        {"op": "subscribe", "topic": "/flag", "throttle_rate": "fast"},
        {"op": "subscribe", "topic": ""},
        {"op": "publish", "topic": "/flag", "msg": {"data": True, "extra": 1}},
        {"op": "auth", "mac": "x"},
        {"op": 5},
        {"op": "set_level", "level": "loud"},
    ],
)
def test_bad_requests_are_refused_silently_unless_status_was_asked_for(
    bus: Bus, loop: asyncio.AbstractEventLoop, talker: Node, request_: dict[str, Any]
) -> None:
    talker.create_publisher(Bool, "/flag", 10)
    with bus.activate():
        Node("setpoints").create_publisher(Vector3, "/uav/input/position", 1)
    topics_before = dict(bus.topics)
    quiet = RosbridgeSession(bus, loop)
    quiet.handle(request_)
    assert quiet.stats.refused == 1 and drain(quiet) == []  # roslibpy raises on a status op
    told = RosbridgeSession(bus, loop)
    told.handle({"op": "set_level", "level": "error"})
    told.handle(dict(request_, id="r1"))
    (status,) = drain(told)
    assert status["op"] == "status" and status["level"] == "error" and status["id"] == "r1"
    assert bus.topics == topics_before


def test_call_service_answers_with_the_request_id(
    bus: Bus, executor: Executor, loop: asyncio.AbstractEventLoop
) -> None:
    trigger = get_service_type("std_srvs/srv/Trigger")

    def serve(_request: Any, response: Any) -> Any:
        response.success, response.message = True, "done"
        return response

    with bus.activate():
        Node("server").create_service(trigger, "/do_it", serve)
    session = RosbridgeSession(bus, loop)
    session.handle({"op": "call_service", "service": "do_it", "id": "call:1", "args": {}})
    executor.spin_some()
    session.handle({"op": "call_service", "service": "/absent", "id": "call:2"})
    replies = drain(session)
    assert replies[0] == {
        "op": "service_response",
        "service": "do_it",
        "values": {"success": True, "message": "done"},
        "result": True,
        "id": "call:1",
    }
    assert replies[1]["result"] is False and replies[1]["id"] == "call:2"
    assert "does not exist" in replies[1]["values"]
    assert session.pending_calls == 0


def test_a_client_may_hold_only_so_many_topics(bus: Bus, loop: asyncio.AbstractEventLoop) -> None:
    session = RosbridgeSession(bus, loop)
    for i in range(MAX_TOPICS + 5):
        session.handle({"op": "subscribe", "topic": f"/t{i}", "type": "std_msgs/Bool"})
    assert len(session.subscriptions) == MAX_TOPICS and session.stats.refused == 5


def test_closing_a_session_leaves_no_node_or_topic(bus: Bus, loop: asyncio.AbstractEventLoop) -> None:
    session = RosbridgeSession(bus, loop)
    session.handle({"op": "subscribe", "topic": "/a", "type": "std_msgs/Bool"})
    session.handle({"op": "advertise", "topic": "/b", "type": "std_msgs/Int64"})
    session.close()
    assert not any(n.get_name().startswith("_rosbridge") for n in bus.nodes)
    assert "/a" not in bus.topics and "/b" not in bus.topics
