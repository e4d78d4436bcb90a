"""Fixtures shared by the unit tests: a bus on a manual clock, and its executor.

Time moves only when a test moves it (``executor.spin_until`` / ``spin_for``).
"""

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
