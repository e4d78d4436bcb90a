"""``substitutions`` as the evaluator uses them: arguments, ``$(var)``, ``$(env)``, ``$(find-pkg-share)``, nesting, errors."""

from __future__ import annotations

from pathlib import Path

import pytest
from launchfiles import TEST_FILE, Parse, error_of, only_node

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


def test_undefined_var_named(parse: Parse) -> None:
    error = error_of(
        parse, '<launch>\n<arg name="robot" default="a"/>\n<node pkg="$(var robt)" exec="b"/></launch>'
    )

    assert error.line == 3
    assert "'robt'" in error.problem and "did you mean 'robot'" in error.problem


def test_var_used_before_declaration_rejected(parse: Parse) -> None:
    error = error_of(parse, '<launch><node pkg="$(var a)" exec="b"/><arg name="a" default="x"/></launch>')

    assert "no argument or variable 'a'" in error.problem


def test_unknown_package_in_find_pkg_share_named(parse: Parse) -> None:
    error = error_of(
        parse, '<launch>\n<include file="$(find-pkg-share visualiser)/launch/view.launch"/></launch>'
    )

    assert (error.file, error.line) == (TEST_FILE, 2) and "package 'visualiser' not found" in error.problem


@pytest.mark.parametrize(
    ("value", "fragment"),
    [
        ("$(eval 1 + 2)", "$(eval) takes 1 argument(s), got 3"),
        ("$(eval '__import__(1)')", "$(eval) does not take Call"),
        ("$(arg x)", "ROS 2 writes $(var NAME)"),
        ("$(find demo)", "$(find-pkg-share PKG)"),
        ("$(anon n)", "unknown substitution $(anon)"),
        ("$(var x", "missing ')'"),
        ("$(var)", "takes 1 argument(s), got 0"),
        ("$(env NOT_SET_ANYWHERE)", "environment variable 'NOT_SET_ANYWHERE' is not set"),
    ],
)
def test_bad_substitution_explained(parse: Parse, value: str, fragment: str) -> None:
    error = error_of(parse, f'<launch>\n<node pkg="a" exec="{value}"/></launch>', environ={})

    assert error.line == 2 and fragment in error.problem
