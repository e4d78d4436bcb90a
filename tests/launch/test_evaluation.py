"""``evaluation``: conditions, groups and namespaces, required arguments, includes and their argument scopes."""

from __future__ import annotations

import pytest
from launchfiles import FindShare, Parse, Write, error_of, file_error_of

from server.services.launch.xml_parser import parse_launch_file

# --- conditions, groups and arguments -----------------------------------------------------


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
    outer = write(
        "outer.launch",
        """<launch>
      <group>
        <push-ros-namespace namespace="uav"/>
        <node pkg="demo" exec="a"/>
        <group><push-ros-namespace namespace="sensors"/><include file="inner.launch"/></group>
        <node pkg="demo" exec="b" namespace="sub"/>
      </group>
      <node pkg="demo" exec="outside"/>
    </launch>""",
    )

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


def test_condition_not_boolean_rejected(parse: Parse) -> None:
    error = error_of(parse, '<launch>\n<node pkg="a" exec="b" if="yes"/></launch>')

    assert error.line == 2 and 'if="yes" is not a condition' in error.problem


def test_missing_required_arg_named(parse: Parse) -> None:
    error = error_of(parse, '<launch>\n  <arg name="robot" description="which"/>\n</launch>')

    assert error.line == 2 and "argument 'robot' is required" in error.problem


def test_undeclared_arg_given_by_caller_rejected(parse: Parse) -> None:
    error = error_of(parse, '<launch><arg name="rate" default="1"/></launch>', args={"rtae": "2"})

    assert error.line == 0 and "'rtae'" in error.problem and "did you mean 'rate'" in error.problem


# --- includes -------------------------------------------------------------------------------


def test_include_args_reach_only_included_file(write: Write, find_share: FindShare) -> None:
    write(
        "child.launch",
        """<launch>
      <arg name="who" default="nobody"/>
      <arg name="level" default="1"/>
      <node pkg="demo" exec="child" name="$(var who)"><param name="level" value="$(var level)"/></node>
    </launch>""",
    )
    parent = write(
        "parent.launch",
        """<launch>
      <arg name="who" default="parent"/>
      <include file="child.launch"><arg name="level" value="7"/></include>
      <node pkg="demo" exec="parent" name="$(var who)"/>
    </launch>""",
    )

    description = parse_launch_file(parent, find_package_share=find_share)

    child, parent_node = description.nodes
    assert (child.name, child.parameters) == ("nobody", (("level", 7),))
    assert parent_node.name == "parent"
    assert dict(description.args) == {"who": "parent"}


def test_include_same_file_twice_allowed_and_listed_once(write: Write, find_share: FindShare) -> None:
    write("leaf.launch", '<launch><arg name="n"/><node pkg="demo" exec="leaf" name="$(var n)"/></launch>')
    root = write(
        "root.launch",
        """<launch>
      <include file="$(dirname)/leaf.launch"><arg name="n" value="one"/></include>
      <include file="leaf.launch"><arg name="n" value="two"/></include>
    </launch>""",
    )

    description = parse_launch_file(root, find_package_share=find_share)

    assert [n.name for n in description.nodes] == ["one", "two"]
    assert description.files == (str(root), str(root.parent / "leaf.launch"))


def test_missing_include_names_including_file_and_line(write: Write, find_share: FindShare) -> None:
    path = write("main.launch", '<launch>\n\n  <include file="gone.launch"/>\n</launch>')

    error = file_error_of(path, find_share)

    assert (error.file, error.line) == (str(path), 3)
    assert f"included file not found: {path.parent / 'gone.launch'}" in error.problem


def test_include_cycle_rejected(write: Write, find_share: FindShare) -> None:
    a = write("a.launch", '<launch>\n<include file="b.launch"/></launch>')
    b = write("b.launch", '<launch>\n\n<include file="a.launch"/></launch>')

    error = file_error_of(a, find_share)

    assert (error.file, error.line) == (str(b), 3)
    assert "include cycle" in error.problem and str(a.name) in error.problem


def test_include_self_rejected(write: Write, find_share: FindShare) -> None:
    path = write("self.launch", '<launch><include file="$(dirname)/self.launch"/></launch>')

    assert "include cycle" in file_error_of(path, find_share).problem


def test_error_inside_included_file_names_that_file(write: Write, find_share: FindShare) -> None:
    child = write("child.launch", '<launch>\n  <node pkg="a"/>\n</launch>')
    parent = write("parent.launch", '<launch><include file="child.launch"/></launch>')

    error = file_error_of(parent, find_share)

    assert (error.file, error.line) == (str(child), 2)


def test_include_missing_required_arg_names_the_include(write: Write, find_share: FindShare) -> None:
    child = write("child.launch", '<launch>\n  <arg name="robot"/>\n</launch>')
    parent = write("parent.launch", '<launch>\n<include file="child.launch"/></launch>')

    error = file_error_of(parent, find_share)

    assert (error.file, error.line) == (str(child), 2)
    assert "argument 'robot' is required" in error.problem and f"{parent}:2" in error.problem


def test_include_passing_undeclared_arg_rejected(write: Write, find_share: FindShare) -> None:
    write("child.launch", '<launch><arg name="robot" default="a"/></launch>')
    parent = write(
        "parent.launch",
        '<launch><include file="child.launch">\n<arg name="robto" value="b"/></include></launch>',
    )

    error = file_error_of(parent, find_share)

    assert (error.file, error.line) == (str(parent), 2)
    assert "declares no argument 'robto'" in error.problem and "did you mean 'robot'" in error.problem


def test_include_of_python_launch_file_needs_a_python_evaluator(write: Write, find_share: FindShare) -> None:
    write("x.launch.py", "")
    path = write("main.launch", '<launch><include file="x.launch.py"/></launch>')

    error = file_error_of(path, find_share)  # parsed without run_python: nothing may run the file

    assert (error.file, error.line) == (str(path), 1)
    assert "Python launch files are not evaluated here" in error.problem
