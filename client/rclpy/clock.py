"""rclpy's Clock: ``node.get_clock().now()`` as an rclpy Time, read from the process's clock (the
bus's, which a test can replace with a manual one)."""

from __future__ import annotations

import math

from node_runtime.bus import Clock as TimeSource
from node_runtime.bus import SystemClock
from rclpy.duration import NS_PER_S
from rclpy.time import ClockType, Time


class Clock:
    def __init__(
        self, *, clock_type: ClockType = ClockType.SYSTEM_TIME, source: TimeSource | None = None
    ) -> None:
        self._clock_type = ClockType(clock_type)
        self._source: TimeSource = source if source is not None else SystemClock()

    @property
    def clock_type(self) -> ClockType:
        return self._clock_type

    def now(self) -> Time:
        t_s = self._source.now()
        sec = math.floor(t_s)  # split first: epoch ns need more than a double's 53 bits
        return Time(nanoseconds=sec * NS_PER_S + round((t_s - sec) * 1e9), clock_type=self._clock_type)

    def __repr__(self) -> str:
        return f"Clock(clock_type={self._clock_type.name})"


class ROSClock(Clock):
    """The ROS time clock; without ``/clock`` (use_sim_time) it reads the system's time, as rclpy's."""

    def __init__(self, *, source: TimeSource | None = None) -> None:
        super().__init__(clock_type=ClockType.ROS_TIME, source=source)

    @property
    def ros_time_is_active(self) -> bool:
        return False


__all__ = ["Clock", "ClockType", "ROSClock"]
