"""rclpy's Time: a point on one clock in whole nanoseconds, with Duration arithmetic.

``Time + Duration`` and ``Time - Duration`` are Times, ``Time - Time`` a Duration; Times of
different clock types do not mix (TypeError), as in rclpy.
"""

from __future__ import annotations

import functools
from enum import IntEnum

from builtin_interfaces.msg import Time as TimeMsg

from rclpy.duration import NS_PER_S, Duration


class ClockType(IntEnum):
    """Printed by name (``ClockType.ROS_TIME``), as rclpy's, which is not a Python IntEnum."""

    UNINITIALIZED = 0
    ROS_TIME = 1
    SYSTEM_TIME = 2
    STEADY_TIME = 3

    def __str__(self) -> str:
        return f"ClockType.{self.name}"

    def __format__(self, spec: str) -> str:
        return format(str(self), spec)


@functools.total_ordering
class Time:
    __slots__ = ("_clock_type", "_ns")

    def __init__(
        self, *, seconds: float = 0, nanoseconds: int = 0, clock_type: ClockType = ClockType.SYSTEM_TIME
    ) -> None:
        total = round(seconds * NS_PER_S) if isinstance(seconds, float) else seconds * NS_PER_S
        total += int(nanoseconds)
        if total < 0:
            raise ValueError("a Time cannot be negative")
        self._ns = total
        self._clock_type = ClockType(clock_type)

    @property
    def nanoseconds(self) -> int:
        return self._ns

    @property
    def clock_type(self) -> ClockType:
        return self._clock_type

    def seconds_nanoseconds(self) -> tuple[int, int]:
        sec, nanosec = divmod(self._ns, NS_PER_S)
        return sec, nanosec

    def to_msg(self) -> TimeMsg:
        sec, nanosec = self.seconds_nanoseconds()
        return TimeMsg(sec=sec, nanosec=nanosec)

    @classmethod
    def from_msg(cls, msg: TimeMsg, clock_type: ClockType = ClockType.ROS_TIME) -> Time:
        return cls(seconds=msg.sec, nanoseconds=msg.nanosec, clock_type=clock_type)

    def __repr__(self) -> str:
        return f"Time(nanoseconds={self._ns}, clock_type={self._clock_type.name})"

    def _same_clock(self, other: Time) -> None:
        if other._clock_type != self._clock_type:
            raise TypeError(
                f"cannot compare or subtract Times of different clocks "
                f"({self._clock_type.name}, {other._clock_type.name})"
            )

    def __add__(self, other: Duration) -> Time:
        if not isinstance(other, Duration):
            return NotImplemented
        return Time(nanoseconds=self._ns + other.nanoseconds, clock_type=self._clock_type)

    __radd__ = __add__

    def __sub__(self, other: Time | Duration) -> Time | Duration:
        if isinstance(other, Time):
            self._same_clock(other)
            return Duration(nanoseconds=self._ns - other._ns)
        if isinstance(other, Duration):
            return Time(nanoseconds=self._ns - other.nanoseconds, clock_type=self._clock_type)
        return NotImplemented

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Time):
            return NotImplemented
        self._same_clock(other)
        return self._ns == other._ns

    def __hash__(self) -> int:
        return hash((self._ns, self._clock_type))

    def __lt__(self, other: Time) -> bool:
        if not isinstance(other, Time):
            return NotImplemented
        self._same_clock(other)
        return self._ns < other._ns
