"""The app against an independent ROS 2-over-Zenoh peer (zenoh-ros2-sdk, whose own CI runs it against
real rmw_zenoh) in its own process: topics both ways, the graph both ways, services both ways."""

from __future__ import annotations

import json

from ros_reference import rihs
from support.app import App, JsonProcess
from websockets.sync.client import connect

from .conftest import definitions, service_text


def test_sdk_subscriber_receives_countdown_and_the_drone_pose(app: App, sdk_peer: JsonProcess) -> None:
    sdk_peer.send(cmd="define", types=definitions("std_msgs/msg/Int64", "geometry_msgs/msg/PoseStamped"))
    sdk_peer.send(
        cmd="subscribe", topic="/countdown", type="std_msgs/msg/Int64", hash=rihs("std_msgs/msg/Int64")
    )
    sdk_peer.send(
        cmd="subscribe",
        topic="/uav/sensors/gps",
        type="geometry_msgs/msg/PoseStamped",
        hash=rihs("geometry_msgs/msg/PoseStamped"),
    )
    countdown = sdk_peer.expect(lambda e: e.get("topic") == "/countdown", "a /countdown message")
    assert 0 <= countdown["msg"]["data"] <= 10
    is_gps = lambda e: e.get("topic") == "/uav/sensors/gps"  # noqa: E731
    sdk_peer.expect(is_gps, "a /uav/sensors/gps message")
    # The newest pose the peer has, against the app's latest read right after: the same pose, but
    # for the few milliseconds of flight between them.
    gps = sdk_peer.newest(is_gps)
    ours = app.get("/api/topics/uav/sensors/gps")["latest"]
    assert gps is not None
    theirs = gps["msg"]["pose"]["position"]
    for axis in "xyz":
        assert abs(theirs[axis] - ours["pose"]["position"][axis]) < 0.2
    assert gps["msg"]["header"]["frame_id"] == ours["header"]["frame_id"]


def test_sdk_publisher_key_a_on_keydown_aborts_the_rocket(app: App, sdk_peer: JsonProcess) -> None:
    sdk_peer.send(cmd="define", types=definitions("keyboard_msgs/msg/Key"))

    def aborted() -> bool:
        latest = app.get("/api/topics/abort_takeoff")["latest"]
        if latest is None or not latest["data"]:
            # The first sample may go out before the routes settle, as with any new ROS 2 publisher.
            sdk_peer.send(
                cmd="publish",
                topic="/keydown",
                type="keyboard_msgs/msg/Key",
                hash=rihs("keyboard_msgs/msg/Key"),
                msg={"code": 97},
            )
            return False
        return True

    app.wait_for(aborted, "/abort_takeoff to turn true")
    app.wait_for(
        lambda: app.get("/api/topics/countdown")["latest"]["data"] == 0, "the countdown to end", 30.0
    )
    assert app.get("/api/topics/cmd_vel")["publish_count"] == 0, "the rocket lifted off after an abort"


def test_sdk_graph_discovery_lists_our_nodes_and_topics(app: App, sdk_peer: JsonProcess) -> None:
    sdk_peer.send(cmd="topics")
    topics = dict(sdk_peer.expect(lambda e: e.get("event") == "topics", "topics")["topics"])
    assert topics["/countdown"] == ["std_msgs/msg/Int64"]
    assert topics["/uav/sensors/gps"] == ["geometry_msgs/msg/PoseStamped"]
    assert "keyboard_msgs/msg/Key" in topics["/keydown"]
    sdk_peer.send(cmd="topic_info", topic="/countdown")
    info = sdk_peer.expect(lambda e: e.get("event") == "topic_info", "topic info")
    assert "CountDownNode" in info["nodes"]


def test_sdk_calls_the_rocket_reset_service(app: App, sdk_peer: JsonProcess) -> None:
    request, response = service_text("std_srvs/srv/Trigger")
    sdk_peer.send(
        cmd="call",
        service="/rocket/reset",
        type="std_srvs/srv/Trigger",
        request=request,
        response=response,
        hash=rihs("std_srvs/srv/Trigger"),
    )
    reply = sdk_peer.expect(lambda e: e.get("event") == "reply", "the reset service's reply")
    assert reply["msg"] == {"success": True, "message": "rocket back on the pad"}


def test_app_calls_a_service_the_sdk_serves(app: App, sdk_peer: JsonProcess) -> None:
    request, response = service_text("example_interfaces/srv/AddTwoInts")
    sdk_peer.send(
        cmd="serve",
        service="/peer/add_two_ints",
        type="example_interfaces/srv/AddTwoInts",
        request=request,
        response=response,
        node="sdk_adder",
        hash=rihs("example_interfaces/srv/AddTwoInts"),
    )
    sdk_peer.expect(lambda e: e.get("event") == "done" and e.get("cmd") == "serve", "the server to be up")
    app.wait_for(
        lambda: any(s["name"] == "/peer/add_two_ints" for s in app.get("/api/services")),
        "the service in our graph",
    )
    answer = app.post("/api/services/peer/add_two_ints", {"request": {"a": 40, "b": 2}})
    assert answer.status_code == 200, answer.text
    assert answer.json() == {
        "service": "/peer/add_two_ints",
        "type": "example_interfaces/srv/AddTwoInts",
        "response": {"sum": 42},
    }


def test_our_graph_lists_the_sdk_node_and_drops_it_when_its_process_is_killed(
    app: App, sdk_peer: JsonProcess
) -> None:
    sdk_peer.send(cmd="define", types=definitions("std_msgs/msg/String"))
    sdk_peer.send(
        cmd="publish",
        topic="/sdk_chatter",
        type="std_msgs/msg/String",
        hash=rihs("std_msgs/msg/String"),
        msg={"data": "hello"},
        node="sdk_talker",
    )

    def talker() -> list[dict[str, object]]:
        return [n for n in app.get("/api/nodes") if n["name"] == "/sdk_talker"]

    app.wait_for(lambda: bool(talker()), "/sdk_talker in our node list")
    assert str(talker()[0]["location"]).startswith("zenoh:")
    topic = app.get("/api/topics/sdk_chatter")
    assert (topic["type"], topic["publishers"]) == ("std_msgs/msg/String", ["/sdk_talker"])
    assert topic["endpoints"][0]["location"] == talker()[0]["location"]
    sdk_peer.kill()
    app.wait_for(lambda: not talker(), "/sdk_talker to leave our node list", timeout_s=5.0)
    assert all(t["name"] != "/sdk_chatter" for t in app.get("/api/topics"))


def test_a_topic_only_another_process_uses_can_be_echoed_and_published_to(
    app: App, sdk_peer: JsonProcess
) -> None:
    sdk_peer.send(cmd="define", types=definitions("std_msgs/msg/String"))
    sdk_peer.send(
        cmd="subscribe", topic="/sdk_inbox", type="std_msgs/msg/String", hash=rihs("std_msgs/msg/String")
    )
    app.wait_for(
        lambda: any(t["name"] == "/sdk_inbox" for t in app.get("/api/topics")), "/sdk_inbox in our graph"
    )

    def delivered() -> bool:
        # No type given: the app learns it from the other process's subscription.
        answer = app.post("/api/publish", {"topic": "/sdk_inbox", "msg": {"data": "from the app"}})
        assert answer.status_code == 200, answer.text
        return sdk_peer.newest(lambda e: e.get("topic") == "/sdk_inbox") is not None

    app.wait_for(delivered, "the peer to receive the app's message")
    assert sdk_peer.newest(lambda e: e.get("topic") == "/sdk_inbox")["msg"] == {"data": "from the app"}  # type: ignore[index]

    with connect(f"ws://127.0.0.1:{app.port}/ws/topics/sdk_echoed?type=std_msgs/msg/String") as echo:
        for i in range(50):  # the first samples may precede the route, as for any new subscription
            sdk_peer.send(
                cmd="publish",
                topic="/sdk_echoed",
                type="std_msgs/msg/String",
                hash=rihs("std_msgs/msg/String"),
                msg={"data": f"n{i}"},
                node="sdk_echo_src",
            )
            try:
                frame = json.loads(echo.recv(timeout=0.5))
                break
            except TimeoutError:
                continue
        else:
            raise AssertionError("the echo socket got none of 50 messages the other process published")
    assert frame["topic"] == "/sdk_echoed" and frame["msg"]["data"].startswith("n")


def test_a_publisher_of_another_type_on_our_topic_is_shown_apart_not_merged(
    app: App, sdk_peer: JsonProcess
) -> None:
    sdk_peer.send(cmd="define", types=definitions("std_msgs/msg/String"))
    sdk_peer.send(
        cmd="publish",
        topic="/countdown",
        type="std_msgs/msg/String",
        hash=rihs("std_msgs/msg/String"),
        msg={"data": "ten"},
        node="sdk_confused",
    )

    def entries() -> list[dict[str, object]]:
        return [t for t in app.get("/api/topics") if t["name"] == "/countdown"]

    app.wait_for(lambda: len(entries()) == 2, "two /countdown entries")
    by_type = {t["type"]: t for t in entries()}
    assert set(by_type) == {"std_msgs/msg/Int64", "std_msgs/msg/String"}
    assert all(t["type_conflict"] for t in by_type.values())
    assert by_type["std_msgs/msg/String"]["publishers"] == ["/sdk_confused"]
    assert "/sdk_confused" not in by_type["std_msgs/msg/Int64"]["publishers"]
    graph = app.get("/api/graph")
    assert any(
        t["name"] == "/countdown [std_msgs/msg/String]" and t["type_conflict"] for t in graph["topics"]
    )
