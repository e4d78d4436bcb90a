"""Injected time: the manual clock only moves forward when told; ROS time stamps."""

from __future__ import annotations

import pytest

from node_runtime.bus import ManualClock, RosTime, SystemClock


def test_manual_clock_set_and_advance_move_time() -> None:
    clock = ManualClock(2.0)
    assert clock.now() == 2.0
    clock.advance(0.5)
    clock.set(4.0)
    assert clock.now() == 4.0


def test_manual_clock_going_back_raises_and_keeps_time() -> None:
    clock = ManualClock(5.0)
    with pytest.raises(ValueError, match="must not go back"):
        clock.set(4.999)
    with pytest.raises(ValueError):
        clock.advance(-1.0)
    assert clock.now() == 5.0


@pytest.mark.parametrize(
    ("seconds", "sec", "nanosec"),
    [
        (0.0, 0, 0),
        (12.5, 12, 500_000_000),
        (1.000000001, 1, 1),
        (1_700_000_000.25, 1_700_000_000, 250_000_000),
    ],
)
def test_ros_time_from_seconds_to_msg_splits_sec_nanosec(seconds: float, sec: int, nanosec: int) -> None:
    msg = RosTime.from_seconds(seconds).to_msg()
    assert (msg.sec, msg.nanosec) == (sec, nanosec)


def test_system_clock_never_goes_back() -> None:
    clock = SystemClock()
    samples = [clock.now() for _ in range(1000)]
    assert samples == sorted(samples)
