"""rclpy's Time, Duration and Clock: arithmetic, comparisons and messages, on a manual clock."""

from __future__ import annotations

import pytest
from builtin_interfaces.msg import Time as TimeMsg
from rclpy.clock import Clock, ROSClock
from rclpy.duration import Duration
from rclpy.time import ClockType, Time

from node_runtime.bus import ManualClock


def test_time_plus_and_minus_a_duration_is_a_time_and_time_minus_time_a_duration() -> None:
    t = Time(seconds=10, nanoseconds=5)
    later = t + Duration(seconds=1.5)
    assert isinstance(later, Time) and later.nanoseconds == 11_500_000_005
    assert (later - t) == Duration(nanoseconds=1_500_000_000)
    earlier = later - Duration(seconds=0.5)
    assert isinstance(earlier, Time) and earlier.seconds_nanoseconds() == (11, 5)
    assert Duration(seconds=2) + t == t + Duration(seconds=2)


def test_times_and_durations_order_as_numbers() -> None:
    a, b = Time(seconds=1), Time(seconds=2)
    assert a < b <= b and b > a and a != b and a == Time(nanoseconds=1_000_000_000)
    assert Duration(seconds=-1) < Duration() < Duration(nanoseconds=1)
    assert max(Duration(seconds=3), Duration(seconds=2)) == Duration(seconds=3)
    assert Duration(seconds=1) * 2.5 == Duration(seconds=2.5)


def test_times_of_different_clocks_do_not_mix() -> None:
    ros = Time(seconds=1, clock_type=ClockType.ROS_TIME)
    steady = Time(seconds=1, clock_type=ClockType.STEADY_TIME)
    with pytest.raises(TypeError, match="different clocks"):
        _ = ros - steady
    with pytest.raises(TypeError, match="different clocks"):
        _ = ros < steady


def test_time_and_duration_go_to_and_from_their_messages() -> None:
    t = Time(seconds=1_700_000_000, nanoseconds=123_456_789)
    msg = t.to_msg()
    assert (msg.sec, msg.nanosec) == (1_700_000_000, 123_456_789)
    assert Time.from_msg(TimeMsg(sec=3, nanosec=4)).nanoseconds == 3_000_000_004
    d = Duration(seconds=-1.25)
    assert Duration.from_msg(d.to_msg()) == d
    with pytest.raises(ValueError, match="negative"):
        Time(nanoseconds=-1)


def test_clock_now_reads_the_injected_time_source() -> None:
    source = ManualClock(1_700_000_000.25)
    clock = ROSClock(source=source)
    first = clock.now()
    assert first.clock_type == ClockType.ROS_TIME and first.seconds_nanoseconds() == (
        1_700_000_000,
        250_000_000,
    )
    source.advance(0.5)
    assert clock.now() - first == Duration(seconds=0.5)
    assert Clock(clock_type=ClockType.STEADY_TIME, source=source).now().clock_type == ClockType.STEADY_TIME
