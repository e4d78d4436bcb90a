"""``node_info``: ros2 node info's view of one node: endpoints, timers and their lateness, parameters, origin."""

from __future__ import annotations

from node_runtime.bus import Bus, Executor, Node
from node_runtime.msgs import Int64
from server.host.introspection import node_info


def _talker(bus: Bus) -> Node:
    talker = Node("talker", context=bus)
    talker.create_publisher(Int64, "/chatter", 10)
    return talker


def test_node_info_lists_endpoints_timers_parameters_and_origin(bus: Bus, executor: Executor) -> None:
    talker = _talker(bus)
    talker.declare_parameter("rate_hz", 2.0)
    talker.origin = {"package": "demo", "executable": "talker"}
    talker.create_timer(0.25, lambda: None)
    executor.spin_until(1.0)
    info = node_info(talker)
    identity = (info["name"], info["namespace"], info["state"], info["crash_reason"])
    assert identity == ("/talker", "/", "active", None)
    assert {"topic": "/chatter", "type": "std_msgs/msg/Int64", "depth": 10} in info["publishers"]
    assert info["subscribers"] == []
    # A manual clock fires every timer exactly on its deadline: no lateness at all.
    assert info["timers"] == [{"period_s": 0.25, "calls": 4, "lateness_p50_ms": 0.0, "lateness_p99_ms": 0.0}]
    assert info["parameters"] == {"use_sim_time": False, "rate_hz": 2.0}  # as every rclpy node
    assert info["origin"] == {"package": "demo", "executable": "talker"}


def test_node_info_timer_never_called_has_no_lateness(bus: Bus) -> None:
    node = Node("idle", context=bus)
    node.create_timer(10.0, lambda: None)
    assert node_info(node)["timers"] == [
        {"period_s": 10.0, "calls": 0, "lateness_p50_ms": None, "lateness_p99_ms": None}
    ]
