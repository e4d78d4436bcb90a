"""``xml_tree``: malformed XML, DOCTYPEs, stray text, size limits and the schema, each error naming file and line."""

from __future__ import annotations

import pytest
from launchfiles import TEST_FILE, FindShare, Parse, Write, error_of, file_error_of

from server.services.launch.description import LaunchFileError
from server.services.launch.xml_parser import MAX_FILE_BYTES, parse_launch_string

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


def test_param_from_file_with_a_name_is_refused_as_ros2_refuses_it(parse: Parse) -> None:
    error = error_of(
        parse, '<launch><node pkg="a" exec="b">\n<param name="p" from="p.yaml"/></node></launch>'
    )

    assert error.line == 2 and "takes no name=" in error.problem


def test_param_without_name_or_from_says_what_it_needs(parse: Parse) -> None:
    error = error_of(parse, '<launch><node pkg="a" exec="b">\n<param value="1"/></node></launch>')

    assert error.line == 2 and "needs name=" in error.problem


def test_declared_arg_with_value_points_to_default(parse: Parse) -> None:
    error = error_of(parse, '<launch>\n<arg name="x" value="1"/></launch>')

    assert error.line == 2 and "default=" in error.problem and "<let" in error.problem


def test_if_and_unless_together_rejected(parse: Parse) -> None:
    assert "both if= and unless=" in error_of(parse, '<launch><group if="1" unless="1"/></launch>').problem
