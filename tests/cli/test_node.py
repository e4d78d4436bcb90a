"""node.py: ``node list | info`` laid out as ros2 prints them (unit and against a live server)."""

from __future__ import annotations

from collections.abc import Callable

from server.cli.node import format_node_info

from .conftest import Result

CRASHED = {
    "name": "/ns/Talker",
    "namespace": "/ns",
    "state": "crashed",
    "crash_reason": "ZeroDivisionError: division by zero",
    "publishers": [
        {"topic": "/rosout", "type": "rcl_interfaces/msg/Log", "depth": 10},
        {"topic": "/chatter", "type": "std_msgs/msg/String", "depth": 10},
    ],
    "subscribers": [
        {"topic": "/b", "type": "std_msgs/msg/Bool", "depth": 1},
        {"topic": "/a", "type": "std_msgs/msg/Int64", "depth": 1},
        {"topic": "/a", "type": "std_msgs/msg/Int64", "depth": 5},
    ],
    "timers": [
        {"period_s": 0.1, "calls": 42, "lateness_p50_ms": 0.25, "lateness_p99_ms": 3.5},
        {"period_s": 2.0, "calls": 0, "lateness_p50_ms": None, "lateness_p99_ms": None},
    ],
    "parameters": {},
    "origin": {},
}


def test_format_node_info_ros2_layout_sorted_without_repeats_then_timers_and_state() -> None:
    assert format_node_info(CRASHED) == (
        "/ns/Talker\n"
        "  Subscribers:\n"
        "    /a: std_msgs/msg/Int64\n"
        "    /b: std_msgs/msg/Bool\n"
        "  Publishers:\n"
        "    /chatter: std_msgs/msg/String\n"
        "    /rosout: rcl_interfaces/msg/Log\n"
        "  Timers:\n"
        "    every 0.100 s: 42 calls, lateness p50 0.25 ms, p99 3.50 ms\n"
        "    every 2.000 s: 0 calls, lateness p50 -, p99 -\n"
        "  State: crashed (ZeroDivisionError: division by zero)"
    )


def test_format_node_info_active_node_has_no_state_line() -> None:
    info = {**CRASHED, "state": "active", "crash_reason": None, "timers": []}
    assert format_node_info(info).splitlines()[-1] == "  Timers:"


# -- against the live server ------------------------------------------------------------------
def test_node_list_fully_qualified_names_without_hidden(ros2lab: Callable[..., Result]) -> None:
    result = ros2lab("node", "list")
    assert result.code == 0, result.err
    names = result.out.splitlines()
    assert {"/CountDownNode", "/MainControllerNode", "/RocketEngineNode", "/KeyboardManager"} <= set(names)
    assert not [n for n in names if n.startswith("/_")]


def test_node_list_all_adds_hidden_nodes(ros2lab: Callable[..., Result]) -> None:
    assert "/_rest_api" in ros2lab("node", "list", "-a").out.splitlines()


def test_node_info_main_controller_subscribers_and_publishers(ros2lab: Callable[..., Result]) -> None:
    result = ros2lab("node", "info", "/MainControllerNode")
    assert result.code == 0, result.err
    lines = result.out.splitlines()
    assert lines[0] == "/MainControllerNode"
    subscribers = lines[lines.index("  Subscribers:") + 1 : lines.index("  Publishers:")]
    publishers = lines[lines.index("  Publishers:") + 1 : lines.index("  Timers:")]
    assert {"    /countdown: std_msgs/msg/Int64", "    /abort_takeoff: std_msgs/msg/Bool"} <= set(subscribers)
    assert "    /cmd_vel: std_msgs/msg/Float64" in publishers


def test_node_info_unknown_node_exits_1(ros2lab: Callable[..., Result]) -> None:
    result = ros2lab("node", "info", "/NoSuchNode")
    assert result.code == 1
    assert "Unable to find node '/NoSuchNode'" in result.err
