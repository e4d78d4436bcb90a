"""rclpy's Duration: a span of time in nanoseconds."""

from __future__ import annotations

from dataclasses import dataclass

from builtin_interfaces.msg import Duration as DurationMsg


@dataclass(frozen=True, init=False)
class Duration:
    nanoseconds: int

    def __init__(self, *, seconds: float = 0.0, nanoseconds: int = 0) -> None:
        object.__setattr__(self, "nanoseconds", round(seconds * 1e9) + int(nanoseconds))

    def to_msg(self) -> DurationMsg:
        sec, nanosec = divmod(self.nanoseconds, 1_000_000_000)
        return DurationMsg(sec=sec, nanosec=nanosec)

    def __add__(self, other: Duration) -> Duration:
        return Duration(nanoseconds=self.nanoseconds + other.nanoseconds)

    def __sub__(self, other: Duration) -> Duration:
        return Duration(nanoseconds=self.nanoseconds - other.nanoseconds)
