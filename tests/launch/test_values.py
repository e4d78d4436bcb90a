"""``values``: parameters typed as ROS launch types them, remaps, the node's respawn, output and legacy attributes."""

from __future__ import annotations

import pytest
from launchfiles import Parse, error_of, only_node


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("true", True),
        ("False", False),
        ("42", 42),
        ("-3", -3),
        ("0.3", 0.3),
        ("1e3", 1000.0),
        ("-.5", -0.5),
        ("abc", "abc"),
        ("'5'", "5"),
        ("1.0.0", "1.0.0"),
        ("", ""),
        ("[1, 2, 3]", [1, 2, 3]),
        ("[0.5, 1.5]", [0.5, 1.5]),
        ("[true, false]", [True, False]),
        ("[a, 'b, c']", ["a", "b, c"]),
        ("[]", []),
    ],
)
def test_param_value_typed_like_ros_launch(text: str, expected: object, parse: Parse) -> None:
    node = only_node(
        parse(f'<launch><node pkg="demo" exec="e"><param name="p" value="{text}"/></node></launch>')
    )

    ((_, value),) = node.parameters
    assert value == expected
    assert type(value) is type(expected)
    if isinstance(value, list) and isinstance(expected, list):
        assert [type(item) for item in value] == [type(item) for item in expected]


def test_nested_params_names_joined_with_dots(parse: Parse) -> None:
    text = """<launch><node pkg="demo" exec="e">
      <param name="gains">
        <param name="p" value="1.0"/>
        <param name="inner"><param name="d" value="2"/></param>
      </param>
    </node></launch>"""

    assert only_node(parse(text)).parameters == (("gains.p", 1.0), ("gains.inner.d", 2))


def test_remaps_kept_in_document_order(parse: Parse) -> None:
    text = """<launch><node pkg="demo" exec="e">
      <remap from="/uav/input/position" to="/keyboardmanager/position"/>
      <remap from="cmd" to="$(env T)"/>
    </node></launch>"""

    node = only_node(parse(text, environ={"T": "/cmd_vel"}))
    assert node.remappings == (("/uav/input/position", "/keyboardmanager/position"), ("cmd", "/cmd_vel"))


def test_node_legacy_type_and_ns_accepted(parse: Parse) -> None:
    node = only_node(parse('<launch><node pkg="demo" type="talker" ns="uav"/></launch>'))

    assert (node.exec, node.namespace) == ("talker", "/uav")


def test_node_respawn_and_delay_parsed(parse: Parse) -> None:
    node = only_node(parse('<launch><node pkg="demo" exec="e" respawn="true" respawn_delay="1.5"/></launch>'))

    assert (node.respawn, node.respawn_delay_s) == (True, 1.5)


def test_param_mixed_list_rejected(parse: Parse) -> None:
    error = error_of(
        parse, '<launch><node pkg="a" exec="b">\n<param name="p" value="[1, 2.5]"/></node></launch>'
    )

    assert error.line == 2 and "parameter 'p'" in error.problem and "mixes float and int" in error.problem


def test_output_value_unknown_rejected(parse: Parse) -> None:
    assert (
        'output="scren"'
        in error_of(parse, '<launch><node pkg="a" exec="b" output="scren"/></launch>').problem
    )
