"""message.py: the MSG argument of ``topic pub`` (YAML or JSON) and ros2's repr of what is published."""

from __future__ import annotations

from typing import Any

import pytest

from server.cli.message import MessageTextError, filled_message, message_repr, parse_message, python_type_name


@pytest.mark.parametrize(
    ("text", "msg"),
    [
        ("{x: 5.0, y: 5.0, z: 10.0}", {"x": 5.0, "y": 5.0, "z": 10.0}),
        ('{"x": 5, "y": 5.5}', {"x": 5, "y": 5.5}),
        ("data: true", {"data": True}),
        ("{data: 'Hello World: 1'}", {"data": "Hello World: 1"}),
        ("{linear: {x: 1.0}, angular: {z: -0.5}}", {"linear": {"x": 1.0}, "angular": {"z": -0.5}}),
        ("", {}),
        ("   ", {}),
        ("{}", {}),
        ("~", {}),
    ],
)
def test_parse_message_yaml_or_json_gives_dict(text: str, msg: dict[str, Any]) -> None:
    assert parse_message(text) == msg


@pytest.mark.parametrize("text", ["[1, 2]", "5", "hello", "true"])
def test_parse_message_not_a_mapping_refused_with_ros2_words(text: str) -> None:
    with pytest.raises(MessageTextError, match="needs to be a dictionary in YAML format"):
        parse_message(text)


def test_parse_message_broken_yaml_says_so() -> None:
    with pytest.raises(MessageTextError, match="not valid YAML"):
        parse_message("{x: 1")


@pytest.mark.parametrize(
    ("text", "where"),
    [
        ("{x: .nan}", "x: nan"),
        ("{pose: {position: {z: .inf}}}", "pose.position.z: inf"),
        ("{a: [1, .nan]}", r"a\[1\]: nan"),
    ],
)
def test_parse_message_non_finite_number_refused_with_its_path(text: str, where: str) -> None:
    with pytest.raises(MessageTextError, match=where):
        parse_message(text)


def test_parse_message_yaml_only_values_refused() -> None:
    with pytest.raises(MessageTextError, match="frame_id"):
        parse_message("{frame_id: 2024-01-01}")  # a date to YAML; quote it to mean text
    with pytest.raises(MessageTextError, match="field names are text"):
        parse_message("{1: 2}")


@pytest.mark.parametrize(
    ("name", "python"),
    [("geometry_msgs/msg/Vector3", "geometry_msgs.msg.Vector3"), ("std_msgs/Bool", "std_msgs.msg.Bool")],
)
def test_python_type_name_both_spellings(name: str, python: str) -> None:
    assert python_type_name(name) == python


def test_message_repr_as_rclpy_prints_it() -> None:
    msg = {"x": 5.0, "y": 5.0, "z": 10.0}
    assert message_repr("geometry_msgs/msg/Vector3", msg) == "geometry_msgs.msg.Vector3(x=5.0, y=5.0, z=10.0)"
    assert message_repr("std_msgs/msg/String", {"data": "hi"}) == "std_msgs.msg.String(data='hi')"
    assert message_repr("std_msgs/msg/Bool", {"data": True}) == "std_msgs.msg.Bool(data=True)"


def test_filled_message_defaults_filled_and_ints_in_float_fields_become_floats() -> None:
    default = {"linear": {"x": 0.0, "y": 0.0, "z": 0.0}, "angular": {"x": 0.0, "y": 0.0, "z": 0.0}}
    filled = filled_message(default, {"linear": {"x": 5}})
    assert filled == {"linear": {"x": 5.0, "y": 0.0, "z": 0.0}, "angular": {"x": 0.0, "y": 0.0, "z": 0.0}}
    assert isinstance(filled["linear"]["x"], float)
    assert filled_message({"data": 0}, {"data": 3}) == {"data": 3}
    assert filled_message({"data": False}, {"data": True}) == {"data": True}
