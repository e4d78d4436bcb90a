"""interface.py: message types shown as ``ros2 interface show`` prints a .msg file."""

from __future__ import annotations

from collections.abc import Callable

from server.cli.interface import schema_lines

from .conftest import Result

VECTOR3 = {"title": "geometry_msgs/msg/Vector3", "type": "object",
           "properties": {n: {"type": "number", "description": "float64"} for n in "xyz"}}  # fmt: skip
TWIST = {
    "title": "geometry_msgs/msg/Twist",
    "type": "object",
    "properties": {"linear": VECTOR3, "angular": VECTOR3},
}


def test_schema_lines_nested_fields_indented_by_tabs_same_package_short_name() -> None:
    assert schema_lines(TWIST) == [
        "Vector3 linear", "\tfloat64 x", "\tfloat64 y", "\tfloat64 z",
        "Vector3 angular", "\tfloat64 x", "\tfloat64 y", "\tfloat64 z",
    ]  # fmt: skip


def test_schema_lines_refs_arrays_and_other_packages() -> None:
    schema = {
        "title": "my_msgs/msg/Path", "type": "object",
        "properties": {
            "header": {"$ref": "#/$defs/Header"},
            "points": {"type": "array", "items": {"$ref": "#/$defs/Point"}},
            "count": {"type": "integer", "description": "uint16", "minimum": 0, "maximum": 65535},
            "tags": {"type": "array", "items": {"type": "string"}},
        },
        "$defs": {
            "Header": {"title": "std_msgs/msg/Header", "type": "object",
                       "properties": {"frame_id": {"type": "string", "description": "string"}}},
            "Point": {"title": "my_msgs/msg/Point", "type": "object",
                      "properties": {"x": {"type": "number"}}},
        },
    }  # fmt: skip
    assert schema_lines(schema) == [
        "std_msgs/Header header", "\tstring frame_id", "Point[] points", "\tfloat64 x", "uint16 count",
        "string[] tags",
    ]  # fmt: skip


# -- against the live server ------------------------------------------------------------------
def test_interface_list_messages_with_ros_names(ros2lab: Callable[..., Result]) -> None:
    result = ros2lab("interface", "list")
    assert result.code == 0, result.err
    lines = result.out.splitlines()
    assert lines[0] == "Messages:"
    assert {"    geometry_msgs/msg/Vector3", "    std_msgs/msg/Int64", "    keyboard_msgs/msg/Key"} <= set(
        lines
    )


def test_interface_show_twist_as_a_msg_file(ros2lab: Callable[..., Result]) -> None:
    result = ros2lab("interface", "show", "geometry_msgs/msg/Twist")
    assert result.code == 0, result.err
    assert result.out.splitlines() == [
        "Vector3 linear", "\tfloat64 x", "\tfloat64 y", "\tfloat64 z",
        "Vector3 angular", "\tfloat64 x", "\tfloat64 y", "\tfloat64 z",
    ]  # fmt: skip


def test_interface_show_header_nested_from_another_package(ros2lab: Callable[..., Result]) -> None:
    lines = ros2lab("interface", "show", "std_msgs/msg/Header").out.splitlines()
    assert lines == ["builtin_interfaces/Time stamp", "\tint32 sec", "\tuint32 nanosec", "string frame_id"]


def test_interface_show_unknown_type_exits_1(ros2lab: Callable[..., Result]) -> None:
    result = ros2lab("interface", "show", "std_msgs/msg/Nope")
    assert result.code == 1
    assert "std_msgs/msg/Nope" in result.err
