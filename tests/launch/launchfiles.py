"""Shared by the launch-file tests: the fixtures' types and helpers that catch a ``LaunchFileError``."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import pytest

from server.services.launch.description import LaunchDescription, LaunchFileError, NodeAction
from server.services.launch.xml_parser import parse_launch_file

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


def only_node(description: LaunchDescription) -> NodeAction:
    (node,) = description.nodes
    return node
