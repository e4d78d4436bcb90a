"""topic.py against a live server: ``topic list | info | echo | hz`` as ros2 prints them."""

from __future__ import annotations

import re
from collections.abc import Callable

from .conftest import LiveServer, Result, Running

ROCKET_TOPICS = ["/abort_takeoff", "/cmd_vel", "/countdown", "/keydown", "/keyup", "/sensor_vel"]


def test_topic_list_one_name_per_line_sorted(ros2lab: Callable[..., Result]) -> None:
    result = ros2lab("topic", "list")
    assert result.code == 0, result.err
    names = result.out.splitlines()
    assert set(ROCKET_TOPICS) <= set(names)
    assert names == sorted(names)
    assert "/rosout" not in names


def test_topic_list_show_types_in_brackets(ros2lab: Callable[..., Result]) -> None:
    lines = ros2lab("topic", "list", "-t").out.splitlines()
    assert "/countdown [std_msgs/msg/Int64]" in lines
    assert "/sensor_vel [std_msgs/msg/Float64]" in lines


def test_topic_list_hidden_topics_add_rosout(ros2lab: Callable[..., Result]) -> None:
    assert "/rosout" in ros2lab("topic", "list", "--include-hidden-topics").out.splitlines()


def test_topic_info_type_and_counts(live_server: LiveServer, ros2lab: Callable[..., Result]) -> None:
    info = live_server.get("/api/topics/countdown")
    result = ros2lab("topic", "info", "/countdown")
    assert result.code == 0, result.err
    assert result.out == (
        f"Type: std_msgs/msg/Int64\nPublisher count: {len(info['publishers'])}\n"
        f"Subscription count: {len(info['subscribers'])}\n"
    )


def test_topic_info_verbose_names_nodes_and_depths(ros2lab: Callable[..., Result]) -> None:
    out = ros2lab("topic", "info", "-v", "countdown").out
    assert (
        "Node name: CountDownNode\nNode namespace: /\nTopic type: std_msgs/msg/Int64\nEndpoint type: PUBLISHER"
        in out
    )
    assert "Node name: MainControllerNode" in out
    assert "  History (Depth): KEEP_LAST (1000)" in out


def test_topic_info_unknown_topic_exits_1(ros2lab: Callable[..., Result]) -> None:
    result = ros2lab("topic", "info", "/no_such_topic")
    assert result.code == 1
    assert "/no_such_topic" in result.err


def test_topic_echo_once_prints_one_countdown_message(
    live_server: LiveServer, ros2lab: Callable[..., Result]
) -> None:
    live_server.post("/api/rocket/reset")  # the countdown runs for 11 s after each (re)start
    result = ros2lab("topic", "echo", "--once", "/countdown")
    assert result.code == 0, result.err
    assert re.fullmatch(r"data: (10|[0-9])\n---\n", result.out), result.out


def test_topic_echo_field_prints_the_bare_value(ros2lab: Callable[..., Result]) -> None:
    result = ros2lab("topic", "echo", "--once", "--field", "data", "/sensor_vel")
    assert result.code == 0, result.err
    value, separator = result.out.splitlines()
    float(value)
    assert separator == "---"


def test_topic_echo_type_waits_for_a_new_topic_and_field_selects_nested(
    live_server: LiveServer, ros2lab: Callable[..., Result], start: Callable[..., Running]
) -> None:
    echo = start(
        "topic",
        "echo",
        "--once",
        "--field",
        "pose.position",
        "/cli_pose",
        "--type",
        "geometry_msgs/msg/PoseStamped",
    )
    live_server.wait_until(
        lambda: "/cli_pose" in {t["name"] for t in live_server.get("/api/topics")}, "the echo to subscribe"
    )
    published = ros2lab(
        "topic",
        "pub",
        "-1",
        "/cli_pose",
        "geometry_msgs/msg/PoseStamped",
        "{pose: {position: {x: 1.5, y: 2, z: -3.0}}}",
    )
    assert published.code == 0, published.err
    assert echo.read_until(lambda line: line.startswith("x:")) == "x: 1.5"
    assert echo.read_until(lambda line: True) == "y: 2.0"
    assert echo.read_until(lambda line: True) == "z: -3.0"
    assert echo.read_until(lambda line: True) == "---"
    assert echo.proc.wait(timeout=5) == 0


def test_topic_echo_ctrl_c_exits_0_quietly(start: Callable[..., Running]) -> None:
    echo = start("topic", "echo", "/sensor_vel", "--qos-depth", "5")
    echo.read_until(lambda line: line == "---")
    assert echo.interrupt() == (0, "")


def test_topic_echo_unknown_topic_warns_and_exits_1(ros2lab: Callable[..., Result]) -> None:
    result = ros2lab("topic", "echo", "/no_such_topic")
    assert result.code == 1
    assert "WARNING: topic [/no_such_topic] does not appear to be published yet" in result.err


def test_topic_echo_bad_field_exits_1(ros2lab: Callable[..., Result]) -> None:
    result = ros2lab("topic", "echo", "--field", "nope", "/sensor_vel")
    assert result.code == 1
    assert "Invalid field 'nope'" in result.err


def test_topic_hz_reports_the_sensor_rate(ros2lab: Callable[..., Result]) -> None:
    result = ros2lab("topic", "hz", "/sensor_vel", "--count", "2")
    assert result.code == 0, result.err
    lines = result.out.splitlines()
    assert len(lines) == 4
    for rate_line, stats_line in zip(lines[::2], lines[1::2], strict=True):
        rate = float(re.fullmatch(r"average rate: (\d+\.\d{3})", rate_line).group(1))  # type: ignore[union-attr]
        stats = re.fullmatch(
            r"\tmin: (\d+\.\d{3})s max: (\d+\.\d{3})s std dev: \d+\.\d{5}s window: \d+", stats_line
        )
        assert stats is not None, stats_line
        # The live lab runs on the wall clock, so a loaded machine may delay a tick: the exact
        # 10 Hz is checked on a manual clock (tests/api/test_introspection.py); here the figures
        # must agree with each other: the mean period lies between the shortest and the longest.
        shortest, longest = float(stats.group(1)), float(stats.group(2))
        assert rate > 0.0 and shortest - 0.001 <= 1.0 / rate <= longest + 0.001, (rate_line, stats_line)


def test_topic_hz_window_bounds_the_statistics(ros2lab: Callable[..., Result]) -> None:
    result = ros2lab("topic", "hz", "/sensor_vel", "--count", "1", "--window", "5")
    assert result.code == 0, result.err
    assert result.out.splitlines()[1].endswith("window: 6")  # ros2 counts messages: periods + 1
