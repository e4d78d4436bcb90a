"""ros2's parameter files and values typed from text, as rcl and ``ros2 param`` read them."""

from __future__ import annotations

from pathlib import Path

import pytest

from node_runtime.params_file import (
    ParamsFileError,
    node_matches,
    parse_params_text,
    read_params_file,
    value_from_text,
)


@pytest.mark.parametrize(
    ("text", "value"),
    [
        ("5", 5),
        ("2.5", 2.5),
        ("true", True),
        ("[1, 2]", [1, 2]),
        ("hello", "hello"),
        ("'5'", "5"),
        ("[1, 'a']", "[1, 'a']"),
        ("{a: 1}", "{a: 1}"),
    ],
)
def test_a_value_is_typed_as_yaml_types_it_and_anything_else_is_its_text(text: str, value: object) -> None:
    assert value_from_text(text) == value and type(value_from_text(text)) is type(value)


@pytest.mark.parametrize(
    ("pattern", "name", "matches"),
    [
        ("/**", "/a/b", True),
        ("talker", "/talker", True),
        ("/talker", "/ns/talker", False),
        ("/ns/talker", "/ns/talker", True),
        ("/**/talker", "/x/y/talker", True),
        ("/ns/*", "/ns/a", True),
        ("/ns/*", "/ns/a/b", False),
        ("/ns/ta*", "/ns/talker", True),
    ],
)
def test_node_patterns_match_as_rcl_matches_them(pattern: str, name: str, matches: bool) -> None:
    assert node_matches(pattern, name) is matches


def test_sections_nest_namespaces_and_parameters_and_apply_in_file_order() -> None:
    parsed = parse_params_text(
        "/**:\n  ros__parameters:\n    a: 1\nns:\n  talker:\n    ros__parameters:\n"
        "      a: 2\n      gains: {p: 0.5}\n",
        "p.yaml",
    )
    assert parsed.for_node("/ns/talker") == {"a": 2, "gains.p": 0.5}
    assert parsed.for_node("/elsewhere") == {"a": 1}
    assert parsed.every_section(use_wildcard=False) == {"a": 2, "gains.p": 0.5}


@pytest.mark.parametrize(
    ("text", "problem"),
    [
        ("talker:\n  ros__parameters:\n    a: [1\n", r"^f\.yaml:\d+: not valid YAML"),
        ("- just\n- a list\n", r"^f\.yaml: not a parameters file"),
        ("talker:\n  ros__parameters: 5\n", r"^f\.yaml: talker: ros__parameters is not a map"),
        ("talker:\n  ros__parameters:\n    a: [1, x]\n", r"^f\.yaml: talker: parameter 'a' has no value"),
    ],
)
def test_a_file_that_is_not_a_parameters_file_is_one_line_naming_it(text: str, problem: str) -> None:
    with pytest.raises(ParamsFileError, match=problem):
        parse_params_text(text, "f.yaml")


def test_reading_names_the_file_and_the_yaml_line(tmp_path: Path) -> None:
    path = tmp_path / "bad.yaml"
    path.write_text("talker:\n  ros__parameters:\n    a: 1\n   b: 2\n")
    with pytest.raises(ParamsFileError, match=rf"^{path}:4: not valid YAML") as caught:
        read_params_file(path)
    assert "\n" not in str(caught.value)
    with pytest.raises(ParamsFileError, match="cannot read it"):
        read_params_file(tmp_path / "missing.yaml")
    path.write_text("talker:\n  ros__parameters:\n    a: 1\n    b: 2\n")  # the same file, fixed
    assert read_params_file(path).for_node("/talker") == {"a": 1, "b": 2}
