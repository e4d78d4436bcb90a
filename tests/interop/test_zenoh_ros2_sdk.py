"""The app against an independent ROS 2-over-Zenoh peer (zenoh-ros2-sdk, whose own CI runs it against
real rmw_zenoh) in its own process: topics both ways, the graph both ways, services both ways."""

from __future__ import annotations

from ros_reference import ROS_REFERENCE_HASHES

from .conftest import App, JsonProcess, definitions, service_text


def rihs(type_name: str) -> str:
    return "RIHS01_" + ROS_REFERENCE_HASHES[type_name]


def test_sdk_subscriber_receives_countdown_and_the_drone_pose(app: App, sdk_peer: JsonProcess) -> None:
    sdk_peer.send(cmd="define", types=definitions("std_msgs/msg/Int64", "geometry_msgs/msg/PoseStamped"))
    sdk_peer.send(
        cmd="subscribe", topic="/countdown", type="std_msgs/msg/Int64", hash=rihs("std_msgs/msg/Int64")
    )
    sdk_peer.send(cmd="subscribe", topic="/uav/sensors/gps", type="geometry_msgs/msg/PoseStamped",
                  hash=rihs("geometry_msgs/msg/PoseStamped"))  # fmt: skip
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
            sdk_peer.send(cmd="publish", topic="/keydown", type="keyboard_msgs/msg/Key",
                          hash=rihs("keyboard_msgs/msg/Key"), msg={"code": 97})  # fmt: skip
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
    sdk_peer.send(cmd="call", service="/rocket/reset", type="std_srvs/srv/Trigger", request=request,
                  response=response, hash=rihs("std_srvs/srv/Trigger"))  # fmt: skip
    reply = sdk_peer.expect(lambda e: e.get("event") == "reply", "the reset service's reply")
    assert reply["msg"] == {"success": True, "message": "rocket back on the pad"}


def test_app_calls_a_service_the_sdk_serves(app: App, sdk_peer: JsonProcess) -> None:
    request, response = service_text("example_interfaces/srv/AddTwoInts")
    sdk_peer.send(cmd="serve", service="/peer/add_two_ints", type="example_interfaces/srv/AddTwoInts",
                  request=request, response=response, node="sdk_adder",
                  hash=rihs("example_interfaces/srv/AddTwoInts"))  # fmt: skip
    sdk_peer.expect(lambda e: e.get("event") == "done" and e.get("cmd") == "serve", "the server to be up")
    app.wait_for(
        lambda: any(s["name"] == "/peer/add_two_ints" for s in app.get("/api/services")),
        "the service in our graph",
    )
    answer = app.post("/api/services/peer/add_two_ints", {"request": {"a": 40, "b": 2}})
    assert answer.status_code == 200, answer.text
    assert answer.json() == {
        "service": "/peer/add_two_ints", "type": "example_interfaces/srv/AddTwoInts", "response": {"sum": 42},
    }  # fmt: skip
