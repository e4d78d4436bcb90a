"""The generated message classes are current with the definitions, and declare what they hold."""

from __future__ import annotations

import typing
from pathlib import Path

import numpy
import numpy.typing
import pytest

from node_runtime.msgs import Message, get_type, type_names
from node_runtime.msgs.generate import generated_files

FILES = generated_files()  # the message modules and the client's packages, written once here
ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("path", sorted(FILES), ids=lambda p: p.relative_to(ROOT).as_posix())
def test_generated_module_matches_the_definitions(path: Path) -> None:
    assert path.is_file() and path.read_text(encoding="utf-8") == FILES[path], (
        f"{path.relative_to(ROOT)} is stale: run `python -m node_runtime.msgs.generate` after editing "
        "node_runtime/msgs/interfaces or node_runtime/msgs/ros_packages.txt"
    )


@pytest.mark.parametrize("name", type_names())
def test_generated_class_annotates_every_field_and_constant(name: str) -> None:
    cls: type[Message] = get_type(name)
    # numpy is imported for the annotations only when type checking (it loads at the first array)
    hints = typing.get_type_hints(cls, localns={"np": numpy, "npt": numpy.typing})
    assert [f.name for f in cls.FIELDS] == list(cls.__slots__)
    assert all(f.name in hints for f in cls.FIELDS)
    assert all(c.name in hints and getattr(cls, c.name) == c.value for c in cls.SPEC.constants)
