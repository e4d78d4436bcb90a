"""A student's Node subclass names its attributes freely: any name rclpy's Node does not define as
API (``self.state``, ``self.bus``, ``self.timer`` ...) is the subclass's own, and the node's
publishers, subscriptions, timers and services still work. In one process without Zenoh."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import pytest
import rclpy
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from std_msgs.msg import String
from std_srvs.srv import SetBool

BOUND_S = 10.0  # every wait ends sooner, on a future; this only bounds a broken run
# Names a student plausibly gives attributes, none of them rclpy Node's API (which has, for
# example, executor, context, handle, publishers and timers as properties of its own).
STUDENT_NAMES = (
    "state",
    "bus",
    "origin",
    "crash_reason",
    "clock",
    "timer",
    "publisher",
    "subscription",
    "service",
    "client",
    "name",
    "namespace",
    "logger",
    "parameters",
    "node",
    "count",
    "publisher_type",
    "subscription_type",
    "timer_type",
    "service_type",
    "callback_group",
)


@pytest.fixture
def context(monkeypatch: pytest.MonkeyPatch) -> Iterator[rclpy.Context]:
    monkeypatch.setenv("ROS2LAB_NO_ZENOH", "1")
    ctx = rclpy.Context()
    with rclpy.init(args=[], context=ctx):
        yield ctx


class Busy(Node):
    """Sets every name in STUDENT_NAMES to a value of its own before and after making entities."""

    def __init__(self, context: rclpy.Context) -> None:
        for name in STUDENT_NAMES:
            setattr(self, name, f"student's {name}")
        super().__init__("busy", context=context)
        for name in STUDENT_NAMES:
            setattr(self, name, f"student's {name}")
        self.heard: list[str] = []
        self.ticks = 0
        self.pub = self.create_publisher(String, "chatter", 10)
        self.sub = self.create_subscription(String, "chatter", lambda m: self.heard.append(m.data), 10)
        self.tick_timer = self.create_timer(0.01, self.tick)
        self.srv = self.create_service(SetBool, "flip", self.flip)
        for name in STUDENT_NAMES:
            setattr(self, name, False)

    def tick(self) -> None:
        self.ticks += 1
        self.pub.publish(String(data=f"tick {self.ticks}"))

    def flip(self, request: Any, response: Any) -> Any:
        response.success = request.data != self.state
        self.state = request.data
        self.get_logger().info(f"state is {self.state}")
        return response


def test_a_subclass_using_names_rclpy_leaves_free_still_publishes_ticks_and_serves(
    context: rclpy.Context,
) -> None:
    node = Busy(context)
    caller = Node("caller", context=context)
    client = caller.create_client(SetBool, "flip")
    executor = SingleThreadedExecutor(context=context)
    executor.add_node(node)
    executor.add_node(caller)
    future = client.call_async(SetBool.Request(data=True))
    executor.spin_until_future_complete(future, timeout_sec=BOUND_S)
    assert future.done() and future.result().success
    assert node.state is True
    while len(node.heard) < 2:
        executor.spin_once(timeout_sec=BOUND_S)
    assert node.heard[:2] == ["tick 1", "tick 2"]
    assert node.get_name() == "busy" and node.get_clock().now().nanoseconds > 0
    assert all(getattr(node, name) is False for name in STUDENT_NAMES if name != "state")
    node.destroy_node()
    caller.destroy_node()


def test_a_name_rclpy_does_not_have_is_missing_until_the_subclass_sets_it(context: rclpy.Context) -> None:
    node = Node("plain", context=context)
    for name in ("state", "bus", "origin", "crash_reason"):
        assert not hasattr(node, name), name
    node.destroy_node()
