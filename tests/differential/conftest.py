"""The oracle's interpreter and a Zenoh router for the lab's side (harness.py)."""

from __future__ import annotations

import sys
from collections.abc import Iterator
from pathlib import Path

import pytest
from support.app import free_port

from .harness import MissingOracle, oracle_python, zenoh_router


@pytest.fixture(scope="module")
def oracle() -> Path:
    """ROS 2's rclpy in this venv's oracle/; its absence fails the test, it never skips it."""
    try:
        return oracle_python(Path(sys.prefix))
    except MissingOracle as exc:
        pytest.fail(str(exc), pytrace=False)


@pytest.fixture(scope="module")
def router() -> Iterator[str]:
    with zenoh_router(free_port()) as endpoint:
        yield endpoint
