"""format.py: messages as ``ros2 topic echo`` prints them, ``--field``, and ``topic hz`` lines."""

from __future__ import annotations

from typing import Any

import pytest

from server.cli.format import FieldError, echo_text, hz_report, message_to_yaml, parse_field, select_field

POSE_STAMPED = {
    "header": {"stamp": {"sec": 12, "nanosec": 500}, "frame_id": "world"},
    "pose": {
        "position": {"x": 5.0, "y": -1.5, "z": 10.0},
        "orientation": {"x": 0.0, "y": 0.0, "z": 0.0, "w": 1.0},
    },
}


def test_message_to_yaml_nested_message_indents_fields_in_order() -> None:
    assert message_to_yaml(POSE_STAMPED) == (
        "header:\n"
        "  stamp:\n"
        "    sec: 12\n"
        "    nanosec: 500\n"
        "  frame_id: world\n"
        "pose:\n"
        "  position:\n"
        "    x: 5.0\n"
        "    y: -1.5\n"
        "    z: 10.0\n"
        "  orientation:\n"
        "    x: 0.0\n"
        "    y: 0.0\n"
        "    z: 0.0\n"
        "    w: 1.0\n"
    )


@pytest.mark.parametrize(
    ("value", "line"),
    [
        (5.0, "x: 5.0"),
        (0.1, "x: 0.1"),
        (1e-7, "x: 1.0e-07"),
        (1.5e20, "x: 1.5e+20"),
        (-0.0, "x: -0.0"),
        (1680.0945851211152, "x: 1680.0945851211152"),
    ],
)
def test_message_to_yaml_floats_print_as_ros2_prints_them(value: float, line: str) -> None:
    assert message_to_yaml({"x": value}) == line + "\n"


def test_message_to_yaml_ints_and_bools_are_bare() -> None:
    assert message_to_yaml({"data": 7, "ok": True}) == "data: 7\nok: true\n"


@pytest.mark.parametrize(
    ("text", "line"),
    [
        ("hello", "data: hello"),
        ("", "data: ''"),
        ("Hello World: 1", "data: 'Hello World: 1'"),
        ("123", "data: '123'"),
        ("true", "data: 'true'"),
    ],
)
def test_message_to_yaml_strings_quoted_only_where_yaml_needs_it(text: str, line: str) -> None:
    assert message_to_yaml({"data": text}) == line + "\n"


def test_message_to_yaml_arrays_block_style_and_abbreviated_with_no_arr() -> None:
    assert message_to_yaml({"data": [1, 2]}) == "data:\n- 1\n- 2\n"
    assert message_to_yaml({"data": [1, 2]}, no_arr=True) == "data: '<sequence length: 2>'\n"


def test_message_to_yaml_long_strings_and_arrays_truncated_like_ros2() -> None:
    text = message_to_yaml({"s": "abcdef", "a": [1, 2, 3]}, truncate_length=2)
    assert text == "s: ab...\na:\n- 1\n- 2\n- '...'\n"
    assert message_to_yaml({"s": "abcdef"}, truncate_length=None) == "s: abcdef\n"


def test_echo_text_whole_message_ends_with_separator() -> None:
    assert echo_text({"data": 5}) == "data: 5\n---\n"


def test_echo_text_field_of_nested_message_prints_that_part_only() -> None:
    assert echo_text(POSE_STAMPED, ["pose", "position"]) == "x: 5.0\ny: -1.5\nz: 10.0\n---\n"


@pytest.mark.parametrize(
    ("msg", "field", "text"),
    [
        ({"data": 5.0}, ["data"], "5.0\n---\n"),
        ({"data": True}, ["data"], "True\n---\n"),
        ({"data": "a: b"}, ["data"], "a: b\n---\n"),
        (POSE_STAMPED, ["header", "frame_id"], "world\n---\n"),
    ],
)
def test_echo_text_primitive_field_prints_bare_as_ros2(
    msg: dict[str, Any], field: list[str], text: str
) -> None:
    assert echo_text(msg, field) == text


def test_select_field_unknown_field_names_where_it_failed() -> None:
    with pytest.raises(FieldError, match=r"Invalid field 'pose\.nope': pose has no field 'nope'"):
        select_field(POSE_STAMPED, ["pose", "nope"])
    with pytest.raises(FieldError, match=r"pose\.position\.x has no field 'y'"):
        select_field(POSE_STAMPED, ["pose", "position", "x", "y"])


def test_parse_field_dotted_path_splits_and_skips_empty_parts() -> None:
    assert parse_field("pose.position") == ["pose", "position"]
    assert parse_field(".pose..position.") == ["pose", "position"]
    assert parse_field(None) is None
    with pytest.raises(FieldError):
        parse_field("..")


def test_hz_report_two_lines_with_window_counting_messages() -> None:
    stats = {"rate_hz": 10.0, "min_s": 0.1, "max_s": 0.1, "std_dev_s": 0.0, "window": 10}
    assert hz_report(stats) == "average rate: 10.000\n\tmin: 0.100s max: 0.100s std dev: 0.00000s window: 11"
