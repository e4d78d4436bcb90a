"""Fixtures for the launch-file tests: a fake package index, a string parser, a file writer."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import pytest

from server.services.launch.description import LaunchDescription
from server.services.launch.xml_parser import parse_launch_string

SHARE = Path(__file__).resolve().parent / "data" / "share"
EMPTY_PACKAGES = frozenset({"simple_sim", "simple_control", "keyboard", "demo"})


class FakePackageNotFound(LookupError):
    pass


def _share_of(pkg: str) -> Path:
    if (SHARE / pkg).is_dir() or pkg in EMPTY_PACKAGES:
        return SHARE / pkg
    raise FakePackageNotFound(pkg)


@pytest.fixture
def share_dir() -> Path:
    """``data/share``: one folder per package, as ``$(find-pkg-share PKG)`` sees them."""
    return SHARE


@pytest.fixture
def find_share() -> Callable[[str], Path]:
    """The packages under ``data/share`` plus a few without files; anything else is unknown."""
    return _share_of


@pytest.fixture
def parse() -> Callable[..., LaunchDescription]:
    """Parse launch XML text as ``/lab/test.launch``; keyword arguments go to the parser."""

    def parse_text(text: str, args: Mapping[str, str] | None = None, **kwargs: Any) -> LaunchDescription:
        return parse_launch_string(
            text, filename="/lab/test.launch", args=args or {}, find_package_share=_share_of, **kwargs
        )

    return parse_text


@pytest.fixture
def write(tmp_path: Path) -> Callable[[str, str], Path]:
    """Write ``text`` to ``tmp_path / name`` and return the path."""

    def write_file(name: str, text: str) -> Path:
        path = tmp_path / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
        return path

    return write_file
