"""The launch XML parser on broken files: every error names the file, the line and the problem."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import pytest

from server.launch.description import LaunchDescription, LaunchFileError
from server.launch.xml_parser import MAX_FILE_BYTES, parse_launch_file, parse_launch_string

Write = Callable[[str, str], Path]
Parse = Callable[..., LaunchDescription]
FindShare = Callable[[str], Path]
TEST_FILE = "/lab/test.launch"  # the name the ``parse`` fixture gives its text


def error_of(parse: Parse, text: str, **kwargs: object) -> LaunchFileError:
    with pytest.raises(LaunchFileError) as caught:
        parse(text, **kwargs)
    return caught.value


def file_error_of(path: Path, find_share: FindShare, **kwargs: object) -> LaunchFileError:
    with pytest.raises(LaunchFileError) as caught:
        parse_launch_file(path, find_package_share=find_share, **kwargs)  # type: ignore[arg-type]
    return caught.value


def test_error_str_is_file_line_problem() -> None:
    error = LaunchFileError("a.launch", 3, "boom")

    assert (str(error), error.file, error.line, error.problem) == ("a.launch:3: boom", "a.launch", 3, "boom")


# --- XML level ------------------------------------------------------------------------------


def test_malformed_xml_mismatched_tag_reports_parser_line(parse: Parse) -> None:
    error = error_of(parse, '<launch>\n  <node pkg="a" exec="b">\n</launch>')

    assert (error.file, error.line) == (TEST_FILE, 3)
    assert "malformed XML: mismatched tag" in error.problem


def test_malformed_xml_empty_file_reports_line_one(parse: Parse) -> None:
    error = error_of(parse, "")

    assert error.line == 1 and "malformed XML" in error.problem


def test_doctype_entity_expansion_rejected(parse: Parse) -> None:
    text = '<?xml version="1.0"?>\n<!DOCTYPE launch [<!ENTITY a "aaaa">]>\n<launch>&a;</launch>'

    error = error_of(parse, text)

    assert error.line == 2 and "DOCTYPE" in error.problem


def test_stray_text_inside_element_rejected(parse: Parse) -> None:
    error = error_of(parse, '<launch>\n  node pkg="a"\n</launch>')

    assert "unexpected text" in error.problem and "<launch>" in error.problem


def test_file_over_one_mib_refused(write: Write, find_share: FindShare) -> None:
    path = write("big.launch", "<launch>" + " " * MAX_FILE_BYTES + "</launch>")

    error = file_error_of(path, find_share)

    assert (error.file, error.line) == (str(path), 0) and "larger than" in error.problem


def test_string_over_one_mib_refused(find_share: FindShare) -> None:
    with pytest.raises(LaunchFileError, match="larger than"):
        parse_launch_string(" " * (MAX_FILE_BYTES + 1), filename="x", find_package_share=find_share)


def test_missing_top_level_file_reported(tmp_path: Path, find_share: FindShare) -> None:
    error = file_error_of(tmp_path / "nope.launch", find_share)

    assert error.line == 0 and "not found" in error.problem


# --- schema ---------------------------------------------------------------------------------


def test_root_not_launch_rejected(parse: Parse) -> None:
    error = error_of(parse, "<launh/>")

    assert error.line == 1 and "root element must be <launch>" in error.problem


def test_unknown_element_named_with_suggestion(parse: Parse) -> None:
    error = error_of(parse, '<launch>\n\n  <nod pkg="a" exec="b"/>\n</launch>')

    assert error.line == 3
    assert "unknown element <nod> inside <launch>" in error.problem and "did you mean <node>" in error.problem


def test_unknown_child_of_node_rejected(parse: Parse) -> None:
    error = error_of(
        parse, '<launch>\n<node pkg="a" exec="b">\n  <parm name="x" value="1"/>\n</node></launch>'
    )

    assert error.line == 3 and "<parm> inside <node>" in error.problem


def test_unknown_attribute_named_with_suggestion(parse: Parse) -> None:
    error = error_of(parse, '<launch>\n  <node pkg="a" exce="b"/>\n</launch>')

    assert error.line == 2
    assert "unknown attribute 'exce' on <node>" in error.problem and "did you mean 'exec'" in error.problem


def test_unknown_attribute_in_skipped_group_still_rejected(parse: Parse) -> None:
    error = error_of(
        parse, '<launch>\n<group if="false">\n  <node pkg="a" exec="b" nmae="c"/>\n</group></launch>'
    )

    assert error.line == 3 and "'nmae'" in error.problem


def test_node_missing_pkg_rejected(parse: Parse) -> None:
    error = error_of(parse, '<launch>\n  <node exec="b"/>\n</launch>')

    assert error.line == 2 and "<node> needs the attribute 'pkg'" in error.problem


def test_node_missing_exec_and_type_rejected(parse: Parse) -> None:
    error = error_of(parse, '<launch>\n  <node pkg="a" name="n"/>\n</launch>')

    assert error.line == 2 and "needs exec=" in error.problem and "type=" in error.problem


def test_node_exec_and_type_both_rejected(parse: Parse) -> None:
    assert (
        "both exec= and type="
        in error_of(parse, '<launch><node pkg="a" exec="b" type="b"/></launch>').problem
    )


def test_param_from_file_rejected(parse: Parse) -> None:
    error = error_of(
        parse, '<launch><node pkg="a" exec="b">\n<param name="p" from="p.yaml"/></node></launch>'
    )

    assert error.line == 2 and "parameter files are not supported" in error.problem


def test_declared_arg_with_value_points_to_default(parse: Parse) -> None:
    error = error_of(parse, '<launch>\n<arg name="x" value="1"/></launch>')

    assert error.line == 2 and "default=" in error.problem and "<let" in error.problem


def test_if_and_unless_together_rejected(parse: Parse) -> None:
    assert "both if= and unless=" in error_of(parse, '<launch><group if="1" unless="1"/></launch>').problem


# --- evaluation -----------------------------------------------------------------------------


def test_condition_not_boolean_rejected(parse: Parse) -> None:
    error = error_of(parse, '<launch>\n<node pkg="a" exec="b" if="yes"/></launch>')

    assert error.line == 2 and 'if="yes" is not a condition' in error.problem


def test_missing_required_arg_named(parse: Parse) -> None:
    error = error_of(parse, '<launch>\n  <arg name="robot" description="which"/>\n</launch>')

    assert error.line == 2 and "argument 'robot' is required" in error.problem


def test_undeclared_arg_given_by_caller_rejected(parse: Parse) -> None:
    error = error_of(parse, '<launch><arg name="rate" default="1"/></launch>', args={"rtae": "2"})

    assert error.line == 0 and "'rtae'" in error.problem and "did you mean 'rate'" in error.problem


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
        ("$(eval 1 + 2)", "$(eval ...) is not supported"),
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


# --- includes -------------------------------------------------------------------------------


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


def test_include_of_python_launch_file_rejected(write: Write, find_share: FindShare) -> None:
    path = write("main.launch", '<launch><include file="x.launch.py"/></launch>')

    assert "only XML launch files" in file_error_of(path, find_share).problem
