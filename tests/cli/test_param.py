"""``ros2lab param``'s side of the wire: values typed as ``ros2 param set`` types them, and a
parameters file read as ``ros2 param load`` reads it, with the reader node processes use (its end-to-end tests are in
tests/processes/test_parameters.py, against node processes)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from node_runtime.params_file import ParamsFileError, read_params_file, value_from_text
from server.cli.param import parameter_value, python_value


@pytest.mark.parametrize(
    ("text", "value"),
    [
        ("earth", {"type": 4, "string_value": "earth"}),
        ("5", {"type": 2, "integer_value": 5}),
        ("2.5", {"type": 3, "double_value": 2.5}),
        ("false", {"type": 1, "bool_value": False}),
        ("[1, 2]", {"type": 7, "integer_array_value": [1, 2]}),
        ("[a, b]", {"type": 9, "string_array_value": ["a", "b"]}),
        ("[1, a]", {"type": 4, "string_value": "[1, a]"}),
    ],
)
def test_a_value_is_typed_as_ros2_param_set_types_it(text: str, value: dict[str, Any]) -> None:
    assert parameter_value(value_from_text(text)) == value
    field = next(k for k in value if k != "type")
    assert python_value({**value, "type": value["type"]}) == value[field]


def test_a_file_loads_wildcard_first_then_every_node(tmp_path: Path) -> None:
    path = tmp_path / "p.yaml"
    path.write_text(
        "talker:\n  ros__parameters:\n    rate: 2.0\n    gains: {p: 1}\n"
        "/**:\n  ros__parameters:\n    rate: 1.0\n    shared: x\n"
    )
    assert read_params_file(path).every_section() == {"rate": 2.0, "shared": "x", "gains.p": 1}
    assert read_params_file(path).every_section(use_wildcard=False) == {"rate": 2.0, "gains.p": 1}


@pytest.mark.parametrize(
    ("text", "problem"),
    [
        ("talker:\n  ros__parameters:\n    rate: [1\n", r"p\.yaml:4: not valid YAML"),
        ("just text\n", r"p\.yaml: not a parameters file"),
        ("talker:\n  ros__parameters:\n    rate: [1, [2]]\n", r"parameter 'rate' has no value"),
    ],
)
def test_a_file_that_is_not_one_is_refused_in_one_line(tmp_path: Path, text: str, problem: str) -> None:
    path = tmp_path / "p.yaml"
    path.write_text(text)
    with pytest.raises(ParamsFileError, match=problem) as caught:
        read_params_file(path).every_section()
    assert "\n" not in str(caught.value)
