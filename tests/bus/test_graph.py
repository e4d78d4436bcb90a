"""Topics on the bus: delivery order, keep-last queues, copies, types, and topic lifetime."""

from __future__ import annotations

from typing import Any

import pytest

from node_runtime.bus import (
    Bus,
    DestroyedError,
    Executor,
    NoBusError,
    Node,
    NodeOverrides,
    TopicTypeError,
    UnknownNodeError,
    UnknownTopicError,
)
from node_runtime.msgs import Float64, Int64, PoseStamped


def _collect(node: Node, msg_type: Any, topic: str, depth: int = 10) -> tuple[list[Any], Any]:
    got: list[Any] = []
    sub = node.create_subscription(msg_type, topic, got.append, depth)
    return got, sub


def test_subscription_several_messages_arrive_in_publish_order(bus: Bus, executor: Executor) -> None:
    node = Node("n", context=bus)
    got, _ = _collect(node, Int64, "/x")
    pub = node.create_publisher(Int64, "/x", 10)
    for i in range(7):
        pub.publish(Int64(data=i))
    executor.spin_some()
    assert [m.data for m in got] == list(range(7))


def test_subscription_depth_2_five_published_keeps_last_two_and_counts_drops(
    bus: Bus, executor: Executor
) -> None:
    node = Node("n", context=bus)
    got, sub = _collect(node, Int64, "/x", depth=2)
    pub = node.create_publisher(Int64, "/x", 10)
    for i in range(5):
        pub.publish(Int64(data=i))
    assert sub.dropped == 3
    assert executor.spin_some() == 2
    assert [m.data for m in got] == [3, 4]


def test_subscription_drained_between_publishes_drops_nothing(bus: Bus, executor: Executor) -> None:
    node = Node("n", context=bus)
    got, sub = _collect(node, Int64, "/x", depth=1)
    pub = node.create_publisher(Int64, "/x", 10)
    for i in range(4):
        pub.publish(Int64(data=i))
        executor.spin_some()
    assert [m.data for m in got] == [0, 1, 2, 3]
    assert sub.dropped == 0


def test_publish_callbacks_run_only_when_executor_spins(bus: Bus, executor: Executor) -> None:
    node = Node("n", context=bus)
    got, _ = _collect(node, Int64, "/x")
    pub = node.create_publisher(Int64, "/x", 10)
    assert pub.publish(Int64(data=1)) == 1
    assert pub.publish(Int64(data=2)) == 1
    assert got == []
    assert executor.spin_some() == 2
    assert [m.data for m in got] == [1, 2]


def test_publish_inside_callback_is_queued_not_run_nested(bus: Bus, executor: Executor) -> None:
    node = Node("n", context=bus)
    got_b, _ = _collect(node, Int64, "/b")
    pub_b = node.create_publisher(Int64, "/b", 10)
    seen_during_publish: list[int] = []

    def on_a(msg: Int64) -> None:
        pub_b.publish(Int64(data=msg.data * 10))
        seen_during_publish.append(len(got_b))

    node.create_subscription(Int64, "/a", on_a, 10)
    node.create_publisher(Int64, "/a", 10).publish(Int64(data=4))
    executor.spin_some()
    assert seen_during_publish == [0]
    assert [m.data for m in got_b] == [40]


def test_two_publishers_two_subscriptions_every_subscriber_gets_every_message(
    bus: Bus, executor: Executor
) -> None:
    talker1, talker2 = Node("talker1", context=bus), Node("talker2", context=bus)
    got1, _ = _collect(Node("listener1", context=bus), Int64, "/chatter")
    got2, _ = _collect(Node("listener2", context=bus), Int64, "/chatter")
    pub1 = talker1.create_publisher(Int64, "/chatter", 10)
    pub2 = talker2.create_publisher(Int64, "/chatter", 10)
    assert pub1.publish(Int64(data=1)) == 2
    assert pub2.publish(Int64(data=2)) == 2
    executor.spin_some()
    assert [m.data for m in got1] == [1, 2]
    assert [m.data for m in got2] == [1, 2]
    assert pub1.get_subscription_count() == 2
    assert bus.get_topic("/chatter").publish_count == 2


def test_subscriber_mutating_its_message_leaves_other_subscriber_and_latest(
    bus: Bus, executor: Executor
) -> None:
    node = Node("n", context=bus)
    seen_by_second: list[float] = []

    def vandal(msg: PoseStamped) -> None:
        msg.pose.position.x = -1.0
        msg.header.frame_id = "vandalised"

    node.create_subscription(PoseStamped, "/pose", vandal, 10)
    node.create_subscription(PoseStamped, "/pose", lambda m: seen_by_second.append(m.pose.position.x), 10)
    msg = PoseStamped()
    msg.pose.position.x = 2.0
    node.create_publisher(PoseStamped, "/pose", 10).publish(msg)
    executor.spin_some()
    assert seen_by_second == [2.0]
    latest = bus.get_topic("/pose").latest
    assert latest is not None and latest.pose.position.x == 2.0 and latest.header.frame_id == ""
    assert msg.pose.position.x == 2.0


def test_publisher_mutating_message_after_publish_leaves_queued_copy(bus: Bus, executor: Executor) -> None:
    node = Node("n", context=bus)
    got, _ = _collect(node, Float64, "/v")
    msg = Float64(data=1.0)
    node.create_publisher(Float64, "/v", 10).publish(msg)
    msg.data = 99.0
    executor.spin_some()
    assert [m.data for m in got] == [1.0]
    latest = bus.get_topic("/v").latest
    assert latest is not None and latest.data == 1.0


def test_hand_over_publisher_read_only_subscriptions_share_its_message_others_get_copies(
    bus: Bus, executor: Executor
) -> None:
    """The lab's own nodes: a publisher that builds each message for its publish hands it over, and
    read-only subscriptions share it with the topic's latest (no copy); a plain subscription still
    gets a copy of its own, and what it does to it reaches nobody else."""
    node = Node("n", context=bus)
    shared: list[PoseStamped] = []
    node.create_subscription(PoseStamped, "/pose", shared.append, 10, read_only=True)
    node.create_subscription(PoseStamped, "/pose", shared.append, 10, read_only=True)

    def vandal(msg: PoseStamped) -> None:
        msg.pose.position.x = -1.0

    node.create_subscription(PoseStamped, "/pose", vandal, 10)
    pub = node.create_publisher(PoseStamped, "/pose", 10, hand_over=True)
    msg = PoseStamped()
    msg.pose.position.x = 2.0
    assert pub.publish(msg) == 3
    executor.spin_some()
    latest = bus.get_topic("/pose").latest
    assert len(shared) == 2 and shared[0] is msg and shared[1] is msg and latest is msg
    assert msg.pose.position.x == 2.0  # the plain subscription changed its own copy only


def test_plain_publisher_changing_its_message_after_publish_leaves_read_only_subscription_and_latest(
    bus: Bus, executor: Executor
) -> None:
    """A student's publisher may reuse one message: read-only subscriptions and the latest then
    share one snapshot taken at the publish, never the publisher's object."""
    node = Node("n", context=bus)
    got: list[Float64] = []
    node.create_subscription(Float64, "/v", got.append, 10, read_only=True)
    pub = node.create_publisher(Float64, "/v", 10)
    msg = Float64(data=1.0)
    pub.publish(msg)
    msg.data = 2.0
    pub.publish(msg)
    msg.data = 99.0
    executor.spin_some()
    assert [m.data for m in got] == [1.0, 2.0] and got[0] is not msg
    latest = bus.get_topic("/v").latest
    assert latest is got[1] and latest.data == 2.0


def test_publish_wrong_type_raises_type_error_and_delivers_nothing(bus: Bus, executor: Executor) -> None:
    node = Node("n", context=bus)
    got, _ = _collect(node, Int64, "/x")
    pub = node.create_publisher(Int64, "/x", 10)
    with pytest.raises(TopicTypeError) as err:
        pub.publish(Float64(data=1.0))
    assert isinstance(err.value, TypeError)
    assert "std_msgs/msg/Int64" in str(err.value)
    with pytest.raises(TypeError):
        pub.publish(5)  # type: ignore[arg-type]
    executor.spin_some()
    assert got == []
    topic = bus.get_topic("/x")
    assert topic.publish_count == 0 and topic.latest is None


def test_create_endpoint_conflicting_type_raises(bus: Bus) -> None:
    node = Node("n", context=bus)
    node.create_publisher(Int64, "/x", 10)
    with pytest.raises(TopicTypeError):
        node.create_subscription(Float64, "/x", lambda m: None, 10)
    with pytest.raises(TopicTypeError):
        Node("other", context=bus).create_publisher(Float64, "x", 10)
    assert bus.get_topic("/x").msg_type is Int64
    assert len(bus.get_topic("/x").subscriptions) == 0


def test_destroy_node_last_endpoint_gone_topic_removed(bus: Bus) -> None:
    a, b = Node("a", context=bus), Node("b", context=bus)
    a.create_publisher(Int64, "/only_a", 10)
    a.create_publisher(Int64, "/shared", 10)
    b.create_subscription(Int64, "/shared", lambda m: None, 10)
    assert {"/only_a", "/shared", "/rosout"} <= set(bus.topics)
    assert a.destroy_node() is True
    assert "/only_a" not in bus.topics
    assert "/shared" in bus.topics and bus.get_topic("/shared").publishers == []
    b.destroy_node()
    assert bus.topics == {}
    with pytest.raises(UnknownTopicError):
        bus.get_topic("/shared")
    assert bus.nodes == []


def test_destroy_subscription_pending_messages_not_delivered(bus: Bus, executor: Executor) -> None:
    node = Node("n", context=bus)
    got, sub = _collect(node, Int64, "/x")
    pub = node.create_publisher(Int64, "/x", 10)
    pub.publish(Int64(data=1))
    sub.destroy()
    assert sub.destroyed and sub not in node.subscriptions
    executor.spin_some()
    assert got == []
    assert pub.publish(Int64(data=2)) == 0


def test_destroyed_node_endpoints_raise_on_use(bus: Bus) -> None:
    node = Node("n", context=bus)
    pub = node.create_publisher(Int64, "/x", 10)
    node.destroy_node()
    assert node.destroy_node() is False
    with pytest.raises(DestroyedError):
        pub.publish(Int64(data=1))
    with pytest.raises(DestroyedError):
        node.create_publisher(Int64, "/x", 10)
    with pytest.raises(DestroyedError):
        node.create_timer(1.0, lambda: None)


def test_node_created_outside_activate_without_context_raises() -> None:
    with pytest.raises(NoBusError):
        Node("orphan")


def test_node_created_inside_activate_joins_that_bus(bus: Bus) -> None:
    other = Bus(bus.clock)
    with bus.activate():
        node = Node("n")
    assert node.bus is bus and node in bus.nodes and node not in other.nodes
    with pytest.raises(NoBusError):
        Node("after")


def test_activate_overrides_parameters_reach_declare_parameter(bus: Bus) -> None:
    with bus.activate(NodeOverrides(parameters={"rate_hz": 20.0})):
        node = Node("n")
    assert node.declare_parameter("rate_hz", 10.0).value == 20.0
    assert node.declare_parameter("other", 3).value == 3
    assert node.get_parameters_dict() == {"use_sim_time": False, "rate_hz": 20.0, "other": 3}


def test_activate_overrides_name_renames_node(bus: Bus) -> None:
    with bus.activate(NodeOverrides(name="keyboard")):
        node = Node("keyboard_node")
    assert node.get_name() == "keyboard"
    assert bus.get_node("/keyboard") is node
    assert node.resolve_topic_name("~/state") == "/keyboard/state"
    with pytest.raises(UnknownNodeError):
        bus.get_node("keyboard_node")


def test_activate_overrides_namespace_prefixes_relative_topics(bus: Bus) -> None:
    with bus.activate(NodeOverrides(namespace="/rocket")):
        node = Node("engine")
    node.create_publisher(Float64, "sensor_vel", 1)
    node.create_publisher(Float64, "/cmd_vel", 1)
    assert node.get_fully_qualified_name() == "/rocket/engine"
    assert {"/rocket/sensor_vel", "/cmd_vel"} <= set(bus.topics)


def test_activate_overrides_remapping_moves_topic(bus: Bus, executor: Executor) -> None:
    with bus.activate(NodeOverrides(remappings={"/launch_abort": "/abort_takeoff"})):
        node = Node("controller")
    got, _ = _collect(node, Int64, "/launch_abort")
    Node("rqt", context=bus).create_publisher(Int64, "/abort_takeoff", 10).publish(Int64(data=1))
    executor.spin_some()
    assert [m.data for m in got] == [1]
    assert "/launch_abort" not in bus.topics


def test_activate_block_ends_overrides_do_not_leak(bus: Bus) -> None:
    with bus.activate(NodeOverrides(name="renamed", parameters={"p": 1})):
        first = Node("a")
    with bus.activate():
        second = Node("b")
    assert first.get_name() == "renamed"
    assert second.get_name() == "b"
    assert second.declare_parameter("p", 0).value == 0


def test_add_node_duplicate_name_warns_and_keeps_both(bus: Bus, caplog: pytest.LogCaptureFixture) -> None:
    Node("twin", context=bus)
    with caplog.at_level("WARNING", logger="bus"):
        Node("twin", context=bus)
    assert len(bus.nodes) == 2
    assert any("/twin" in r.getMessage() and "already exists" in r.getMessage() for r in caplog.records)


def test_graph_version_changes_on_every_graph_change(bus: Bus) -> None:
    v0 = bus.graph_version
    node = Node("n", context=bus)
    v1 = bus.graph_version
    pub = node.create_publisher(Int64, "/x", 10)
    v2 = bus.graph_version
    pub.destroy()
    v3 = bus.graph_version
    assert v0 < v1 < v2 < v3


class _OtherProcesses:
    """What the Zenoh transport's RemoteGraph tells the bus: topic names with the types given them."""

    def __init__(self) -> None:
        self.version = 0
        self.types: dict[str, set[str]] = {}

    def topic_types(self) -> dict[str, set[str]]:
        return self.types


def test_known_topics_add_other_processes_topics_whose_type_is_known_and_unambiguous(bus: Bus) -> None:
    node = Node("n", context=bus)
    node.create_publisher(Int64, "/countdown", 10)
    remote = _OtherProcesses()
    remote.types = {
        "/student_pose": {"geometry_msgs/msg/PoseStamped"},
        "/countdown": {"std_msgs/msg/String"},  # this process's type wins: the bridges carry its messages
        "/two_types": {"std_msgs/msg/Float64", "std_msgs/msg/Int64"},
        "/own_type": {"my_pkg/msg/Thing"},
        "/dds_only": {"my_pkg::msg::dds_::Thing_"},
    }
    local = {name: topic.msg_type for name, topic in bus.topics.items()}  # /countdown, /rosout
    assert local["/countdown"] is Int64
    assert bus.known_topics() == local, "no transport yet: this process's topics only"
    before = bus.topics_version
    bus.remote_topics = remote
    assert bus.known_topics() == {**local, "/student_pose": PoseStamped}
    assert bus.topics_version != before
    remote.types["/student_speed"] = {"std_msgs/msg/Float64"}
    remote.version += 1
    assert bus.known_topics()["/student_speed"] is Float64
    changed = bus.topics_version
    node.create_subscription(Float64, "/student_speed", lambda _m: None, 10)
    assert bus.topics_version != changed, "a new local topic moves the version too"
