"""``--ros-args`` as a node process receives them from ``ros2 run`` and ``ros2 launch``."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from client.rclpy._console import console_line, set_threshold
from client.rclpy._ros_args import RosArgsError, parse_ros_args


def test_remaps_params_and_the_programs_own_arguments_are_told_apart() -> None:
    args = parse_ros_args(
        ["--verbose", "--ros-args", "-r", "__node:=talker", "-r", "chatter:=news", "-p", "rate:=5", "--", "x"]
    )
    assert args.node_name == "talker" and args.remappings == {"chatter": "news"}
    assert args.parameters == {"rate": 5} and args.rest == ["--verbose", "x"]


@pytest.mark.parametrize(("text", "level"), [("debug", 10), ("WARN", 30), ("my_node:=error", 40)])
def test_log_level_is_read_as_rcutils_severity(text: str, level: int) -> None:
    assert parse_ros_args(["--ros-args", "--log-level", text]).log_level == level


def test_an_unknown_log_level_is_refused_by_name() -> None:
    with pytest.raises(RosArgsError, match="loud"):
        parse_ros_args(["--ros-args", "--log-level", "loud"])


def test_the_threshold_hides_lines_below_it(capsys: pytest.CaptureFixture[str]) -> None:
    try:
        set_threshold(40)
        console_line(30, "n", "a warning")
        console_line(40, "n", "an error")
    finally:
        set_threshold(20)
    err = capsys.readouterr().err
    assert "an error" in err and "a warning" not in err


NODE = """
import rclpy
from rclpy.node import Node

rclpy.init()
node = Node('quiet')
node.get_logger().info('an info line')
node.get_logger().error('an error line')
rclpy.shutdown()
"""


def test_a_node_started_with_log_level_error_prints_only_errors(tmp_path: Path) -> None:
    script = tmp_path / "quiet.py"
    script.write_text(NODE)
    done = subprocess.run(
        [sys.executable, str(script), "--ros-args", "--log-level", "error"],
        env={**os.environ, "ROS2LAB_NO_ZENOH": "1"},
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
    )
    assert done.returncode == 0, done.stderr
    assert "an error line" in done.stderr and "an info line" not in done.stderr


def test_a_params_file_is_read_at_init_and_one_that_does_not_parse_is_named_with_its_line(
    tmp_path: Path,
) -> None:
    good = tmp_path / "good.yaml"
    good.write_text("/**:\n  ros__parameters:\n    rate: 5\n")
    args = parse_ros_args(["--ros-args", "--params-file", str(good), "-p", "other:=1"])
    assert args.parameters_for("/any/node") == {"rate": 5, "other": 1}
    bad = tmp_path / "bad.yaml"
    bad.write_text("/**:\n  ros__parameters:\n    rate: {5\n")
    with pytest.raises(RosArgsError, match=rf"^{bad}:4: not valid YAML"):
        parse_ros_args(["--ros-args", "--params-file", str(bad)])
    with pytest.raises(RosArgsError, match="--params-file needs a value"):
        parse_ros_args(["--ros-args", "--params-file"])
