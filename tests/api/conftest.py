"""Fixtures for the API tests: the rocket lab behind a TestClient, its lifespan entered."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import ExitStack
from typing import Any

import pytest
from labclient import QUIET_START_DELAY, LabClient, rocket_settings
from support.app_pool import lab_client


@pytest.fixture
def make_lab() -> Iterator[Callable[..., LabClient]]:
    """Start a rocket lab (``start_delay`` in s as the launch takes it; LabSettings and LabLimits overrides)."""
    with ExitStack() as stack:

        def make(start_delay: str = QUIET_START_DELAY, **limits: Any) -> LabClient:
            return LabClient(stack.enter_context(lab_client(rocket_settings(start_delay, **limits))))

        yield make


@pytest.fixture
def rocket_lab(make_lab: Callable[..., LabClient]) -> LabClient:
    """The rocket lab with a countdown that does not start during the test: its topics stay still."""
    return make_lab()


@pytest.fixture
def counting_lab(make_lab: Callable[..., LabClient]) -> LabClient:
    """The rocket lab counting down from the start (10 at once, then 1 Hz)."""
    return make_lab(start_delay="0")
