"""The launch XML parser on valid files: the lab's fly.launch, arguments, includes, params, groups."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import pytest

from server.launch.description import LaunchDescription, NodeAction, SourceLocation
from server.launch.xml_parser import parse_launch_file

Write = Callable[[str, str], Path]
Parse = Callable[..., LaunchDescription]
FindShare = Callable[[str], Path]


@pytest.fixture
def fly(share_dir: Path) -> Path:
    """The lab's fly.launch after checkpoint 3, reconstructed from the lab text."""
    return share_dir / "flightcontroller" / "launch" / "fly.launch"


def only_node(description: LaunchDescription) -> NodeAction:
    (node,) = description.nodes
    return node


# --- the lab's fly.launch -----------------------------------------------------------------


def test_fly_launch_checkpoint3_flattens_includes_in_document_order(fly: Path, find_share: FindShare) -> None:
    description = parse_launch_file(fly, find_package_share=find_share)

    assert [(n.pkg, n.exec, n.name) for n in description.nodes] == [
        ("visualizer", "gui_controller.py", "GUI_Controller_Node"),
        ("flightcontroller", "position_controller.py", "position_controller_node"),
        ("sensor_simulation", "down_facing_camera.py", "down_facing_camera_node"),
        ("sensor_simulation", "pressure.py", "pressure_node"),
        ("simple_sim", "simple_sim_node", None),
        ("simple_control", "keyboard_manager", "keyboard_manager_node"),
        ("keyboard", "keyboard", "keyboard"),
    ]
    assert all(n.output == "screen" for n in description.nodes)
    assert all(n.namespace is None and not n.respawn for n in description.nodes)


def test_fly_launch_params_typed_as_launched(fly: Path, find_share: FindShare) -> None:
    nodes = {n.name: n for n in parse_launch_file(fly, find_package_share=find_share).nodes}

    gains = nodes["position_controller_node"].parameters
    assert gains == (("gains/stable/p", 1), ("gains/stable/i", 0), ("gains/stable/d", 0.3))
    assert [type(value) for _, value in gains] == [int, int, float]
    assert nodes["down_facing_camera_node"].parameters == (("image_path", "construction.jpeg"),)


def test_fly_launch_sim_node_on_exit_shutdown_ends_launch(fly: Path, find_share: FindShare) -> None:
    nodes = parse_launch_file(fly, find_package_share=find_share).nodes

    assert [n.exec for n in nodes if n.shutdown_on_exit] == ["simple_sim_node"]


def test_fly_launch_locations_point_into_each_file(fly: Path, find_share: FindShare, share_dir: Path) -> None:
    description = parse_launch_file(fly, find_package_share=find_share)

    view = str(share_dir / "visualizer" / "launch" / "view.launch")
    assert description.nodes[0].location == SourceLocation(view, 3)
    assert description.nodes[-1].location == SourceLocation(str(fly), 17)
    assert description.files == (
        str(fly),
        view,
        str(share_dir / "flightcontroller" / "launch" / "position.launch"),
        str(share_dir / "sensor_simulation" / "launch" / "sensors.launch"),
    )
    assert dict(description.args) == {}


# --- arguments and substitutions ------------------------------------------------------------

ARGS_LAUNCH = """<launch>
  <arg name="robot" default="uav" description="robot name"/>
  <arg name="rate" default="20"/>
  <node pkg="demo" exec="talker" name="$(var robot)_node">
    <param name="rate_hz" value="$(var rate)"/>
    <param name="topic" value="/$(var robot)/cmd"/>
  </node>
</launch>"""


def test_args_not_given_use_defaults(parse: Parse) -> None:
    description = parse(ARGS_LAUNCH)

    node = only_node(description)
    assert node.name == "uav_node"
    assert node.parameters == (("rate_hz", 20), ("topic", "/uav/cmd"))
    assert dict(description.args) == {"robot": "uav", "rate": "20"}


def test_args_given_override_defaults(parse: Parse) -> None:
    description = parse(ARGS_LAUNCH, args={"rate": "2.5", "robot": "rocket"})

    assert only_node(description).parameters == (("rate_hz", 2.5), ("topic", "/rocket/cmd"))
    assert dict(description.args) == {"robot": "rocket", "rate": "2.5"}


def test_args_result_mapping_is_read_only(parse: Parse) -> None:
    description = parse(ARGS_LAUNCH)

    with pytest.raises(TypeError):
        description.args["rate"] = "1"  # type: ignore[index]


def test_required_arg_given_is_used(parse: Parse) -> None:
    text = '<launch><arg name="pkg"/><node pkg="$(var pkg)" exec="x"/></launch>'

    assert only_node(parse(text, args={"pkg": "demo"})).pkg == "demo"


def test_let_defines_constant_for_later_attributes(parse: Parse) -> None:
    text = """<launch>
      <let name="n" value="a"/><let name="n" value="$(var n)b"/><node pkg="demo" exec="$(var n)"/>
    </launch>"""

    assert only_node(parse(text)).exec == "ab"


def test_env_substitution_uses_injected_environ_and_default(parse: Parse) -> None:
    text = """<launch>
      <node pkg="demo" exec="$(env EXE)" name="$(env MISSING 'fallback_name')"/>
    </launch>"""

    node = only_node(parse(text, environ={"EXE": "talker"}))
    assert (node.exec, node.name) == ("talker", "fallback_name")


def test_substitution_nested_in_argument_is_expanded(parse: Parse) -> None:
    text = '<launch><arg name="which" default="X"/><node pkg="demo" exec="$(env $(var which))"/></launch>'

    assert only_node(parse(text, environ={"X": "found"})).exec == "found"


def test_find_pkg_share_and_dollar_without_paren_kept(share_dir: Path, parse: Parse) -> None:
    text = """<launch>
      <node pkg="demo" exec="e"><param name="p" value="$(find-pkg-share demo)/a$b"/></node>
    </launch>"""

    assert only_node(parse(text)).parameters == (("p", f"{share_dir / 'demo'}/a$b"),)


# --- includes -------------------------------------------------------------------------------


def test_include_args_reach_only_included_file(write: Write, find_share: FindShare) -> None:
    write("child.launch", """<launch>
      <arg name="who" default="nobody"/>
      <arg name="level" default="1"/>
      <node pkg="demo" exec="child" name="$(var who)"><param name="level" value="$(var level)"/></node>
    </launch>""")  # fmt: skip
    parent = write("parent.launch", """<launch>
      <arg name="who" default="parent"/>
      <include file="child.launch"><arg name="level" value="7"/></include>
      <node pkg="demo" exec="parent" name="$(var who)"/>
    </launch>""")  # fmt: skip

    description = parse_launch_file(parent, find_package_share=find_share)

    child, parent_node = description.nodes
    assert (child.name, child.parameters) == ("nobody", (("level", 7),))
    assert parent_node.name == "parent"
    assert dict(description.args) == {"who": "parent"}


def test_include_same_file_twice_allowed_and_listed_once(write: Write, find_share: FindShare) -> None:
    write("leaf.launch", '<launch><arg name="n"/><node pkg="demo" exec="leaf" name="$(var n)"/></launch>')
    root = write("root.launch", """<launch>
      <include file="$(dirname)/leaf.launch"><arg name="n" value="one"/></include>
      <include file="leaf.launch"><arg name="n" value="two"/></include>
    </launch>""")  # fmt: skip

    description = parse_launch_file(root, find_package_share=find_share)

    assert [n.name for n in description.nodes] == ["one", "two"]
    assert description.files == (str(root), str(root.parent / "leaf.launch"))


# --- params and remaps ----------------------------------------------------------------------


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


# --- conditions and groups ------------------------------------------------------------------

CONDITIONS_LAUNCH = """<launch>
  <arg name="kb" default="true"/>
  <node pkg="keyboard" exec="keyboard" if="$(var kb)"/>
  <node pkg="demo" exec="no_keyboard" unless="$(var kb)"/>
  <include file="$(find-pkg-share not_installed)/x.launch" if="0"/>
  <group if="$(var kb)"><node pkg="demo" exec="grouped"/></group>
</launch>"""


@pytest.mark.parametrize(
    ("kb", "execs"),
    [("true", ["keyboard", "grouped"]), ("1", ["keyboard", "grouped"]), ("False", ["no_keyboard"])],
)
def test_if_unless_conditions_select_actions(kb: str, execs: list[str], parse: Parse) -> None:
    assert [n.exec for n in parse(CONDITIONS_LAUNCH, args={"kb": kb}).nodes] == execs


def test_group_push_ros_namespace_prefixes_nodes_and_includes(write: Write, find_share: FindShare) -> None:
    write(
        "inner.launch",
        '<launch><node pkg="demo" exec="inner"/><node pkg="demo" exec="abs" namespace="/top"/></launch>',
    )
    outer = write("outer.launch", """<launch>
      <group>
        <push-ros-namespace namespace="uav"/>
        <node pkg="demo" exec="a"/>
        <group><push-ros-namespace namespace="sensors"/><include file="inner.launch"/></group>
        <node pkg="demo" exec="b" namespace="sub"/>
      </group>
      <node pkg="demo" exec="outside"/>
    </launch>""")  # fmt: skip

    nodes = parse_launch_file(outer, find_package_share=find_share).nodes

    assert [(n.exec, n.namespace) for n in nodes] == [
        ("a", "/uav"),
        ("inner", "/uav/sensors"),
        ("abs", "/top"),
        ("b", "/uav/sub"),
        ("outside", None),
    ]


def test_group_let_does_not_leak_out_of_group(parse: Parse) -> None:
    text = """<launch>
      <let name="n" value="outer"/>
      <group><let name="n" value="inner"/><node pkg="demo" exec="$(var n)"/></group>
      <node pkg="demo" exec="$(var n)"/>
    </launch>"""

    assert [n.exec for n in parse(text).nodes] == ["inner", "outer"]
