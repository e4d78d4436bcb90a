"""rclpy's Node shape: names, parameters, logging to /rosout, the clock, destruction."""

from __future__ import annotations

import logging

import pytest

from node_runtime.bus import Bus, Executor, InvalidNameError, ManualClock, Node
from node_runtime.bus.node import node_logger_name
from node_runtime.msgs import Log, Time


@pytest.mark.parametrize("name", ["", "1node", "my-node", "a b", "ns/node"])
def test_node_invalid_name_raises_and_joins_nothing(bus: Bus, name: str) -> None:
    with pytest.raises(InvalidNameError):
        Node(name, context=bus)
    assert bus.nodes == [] and bus.topics == {}


@pytest.mark.parametrize("namespace", ["/ns/", "/1ns", "/a//b", "/a-b"])
def test_node_invalid_namespace_raises(bus: Bus, namespace: str) -> None:
    with pytest.raises(InvalidNameError):
        Node("n", namespace=namespace, context=bus)
    assert bus.nodes == []


@pytest.mark.parametrize(
    ("namespace", "fq"), [(None, "/talker"), ("/", "/talker"), ("robot", "/robot/talker")]
)
def test_node_namespace_gives_fully_qualified_name(bus: Bus, namespace: str | None, fq: str) -> None:
    node = Node("talker", namespace=namespace, context=bus)
    assert node.get_fully_qualified_name() == fq
    assert bus.get_node(fq) is node


def test_node_declare_parameter_without_override_uses_default(bus: Bus) -> None:
    node = Node("n", context=bus)
    assert node.declare_parameter("allow_repeat", False).value is False
    assert node.get_parameter("allow_repeat").value is False
    assert node.has_parameter("allow_repeat") and not node.has_parameter("other")


def test_node_parameter_overrides_keyword_replaces_default(bus: Bus) -> None:
    node = Node("n", context=bus, parameter_overrides={"seed": 42})
    assert node.declare_parameter("seed", 0).value == 42


def test_node_get_parameter_undeclared_raises(bus: Bus) -> None:
    with pytest.raises(LookupError, match="'missing'"):
        Node("n", context=bus).get_parameter("missing")


def test_node_get_clock_now_to_msg_reads_bus_clock(bus: Bus, clock: ManualClock) -> None:
    node = Node("n", context=bus)
    clock.set(12.5)
    stamp = node.get_clock().now().to_msg()
    assert isinstance(stamp, Time)
    assert (stamp.sec, stamp.nanosec) == (12, 500_000_000)
    clock.advance(0.25)
    assert node.get_clock().now().seconds_nanoseconds() == (12, 750_000_000)


def test_node_logger_info_goes_to_python_logging_and_rosout(
    bus: Bus, clock: ManualClock, executor: Executor, caplog: pytest.LogCaptureFixture
) -> None:
    logs: list[Log] = []
    Node("rqt_console", context=bus).create_subscription(Log, "/rosout", logs.append, 100)
    node = Node("talker", namespace="/ns", context=bus)
    clock.set(3.5)
    with caplog.at_level(logging.INFO):
        node.get_logger().info("Rocket Ready for Countdown")
        node.get_logger().warning("low fuel")
    executor.spin_some()
    assert [(m.name, m.level, m.msg) for m in logs] == [
        ("ns.talker", Log.INFO, "Rocket Ready for Countdown"),  # rcl's logger name: ns.name
        ("ns.talker", Log.WARN, "low fuel"),
    ]
    assert (logs[0].stamp.sec, logs[0].stamp.nanosec) == (3, 500_000_000)
    messages = [r.getMessage() for r in caplog.records]
    assert "[ns.talker] Rocket Ready for Countdown" in messages
    assert "[ns.talker] low fuel" in messages


def test_a_class_worlds_node_logs_under_its_worlds_logger_and_still_on_its_rosout(
    bus: Bus, executor: Executor, caplog: pytest.LogCaptureFixture
) -> None:
    # A class server's console sets one level for every world's nodes (logger "world") and names
    # the world; the lines on the world's own /rosout are as before.
    bus.label = "ada"
    logs: list[Log] = []
    Node("rqt_console", context=bus).create_subscription(Log, "/rosout", logs.append, 100)
    node = Node("talker", namespace="/ns", context=bus)
    with caplog.at_level(logging.INFO):
        node.get_logger().info("Countdown: 3s")
    executor.spin_some()
    assert [(r.name, r.getMessage()) for r in caplog.records] == [
        ("world.ada.ns.talker", "[ns.talker] Countdown: 3s")
    ]
    assert [(m.name, m.msg) for m in logs] == [("ns.talker", "Countdown: 3s")]
    assert node_logger_name(None, "/ns/talker") == "node.ns.talker"  # the lab alone, as before


def test_node_destroy_node_removes_it_from_bus(bus: Bus) -> None:
    node = Node("n", context=bus)
    node.create_timer(1.0, lambda: None)
    assert node.destroy_node() is True
    assert node.state == "destroyed"
    assert node not in bus.nodes
    assert node.timers == [] and node.publishers == [] and node.subscriptions == []
