"""The Message Publisher panel's form: the fields it offers for a type, and the JSON it builds."""

from __future__ import annotations

import yaml

from node_runtime.msgs import Key, PoseStamped, Vector3
from server.peripherals.viewer.publisher_panel import flow_yaml, leaf_fields, nest


def test_leaf_fields_of_vector3_are_x_y_z() -> None:
    assert [path for path, _ in leaf_fields(Vector3)] == ["x", "y", "z"]


def test_leaf_fields_flatten_nested_types_and_skip_the_stamp() -> None:
    paths = [path for path, _ in leaf_fields(PoseStamped)]
    assert paths == [
        "header.frame_id",
        "pose.position.x",
        "pose.position.y",
        "pose.position.z",
        "pose.orientation.x",
        "pose.orientation.y",
        "pose.orientation.z",
        "pose.orientation.w",
    ]


def test_nest_builds_a_message_the_type_accepts() -> None:
    values = {path: (5 if field.kind == "uint16" else field.default) for path, field in leaf_fields(Key)}
    msg = Key.from_dict(nest(values))
    assert msg.code == 5 and msg.modifiers == 5 and msg.header.frame_id == ""


def test_the_preview_is_a_line_ros2_topic_pub_takes() -> None:
    values = {path: field.default for path, field in leaf_fields(PoseStamped)}
    values["pose.position.x"] = 5.0
    line = flow_yaml(nest(values))
    assert "\n" not in line
    assert line.startswith("{header: {frame_id: ''}, pose: {position: {x: 5.0, y: 0.0")
    assert PoseStamped.from_dict(yaml.safe_load(line)).pose.position.x == 5.0
