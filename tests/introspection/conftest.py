"""A bus on a manual clock and its executor: time moves only when a test moves it."""

from __future__ import annotations

import pytest

from server.bus import Bus, Executor, ManualClock


@pytest.fixture
def clock() -> ManualClock:
    return ManualClock()


@pytest.fixture
def bus(clock: ManualClock) -> Bus:
    return Bus(clock)


@pytest.fixture
def executor(bus: Bus) -> Executor:
    return Executor(bus)
