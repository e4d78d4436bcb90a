"""rclpy's Duration: a signed span of time in whole nanoseconds."""

from __future__ import annotations

import functools
from dataclasses import dataclass

from builtin_interfaces.msg import Duration as DurationMsg

NS_PER_S = 1_000_000_000


@functools.total_ordering
@dataclass(frozen=True, init=False, eq=False)
class Duration:
    nanoseconds: int

    def __init__(self, *, seconds: float = 0.0, nanoseconds: int = 0) -> None:
        object.__setattr__(self, "nanoseconds", round(seconds * NS_PER_S) + int(nanoseconds))

    @classmethod
    def from_msg(cls, msg: DurationMsg) -> Duration:
        return cls(seconds=msg.sec, nanoseconds=msg.nanosec)

    def to_msg(self) -> DurationMsg:
        sec, nanosec = divmod(self.nanoseconds, NS_PER_S)
        return DurationMsg(sec=sec, nanosec=nanosec)

    def __repr__(self) -> str:
        return f"Duration(nanoseconds={self.nanoseconds})"

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Duration):
            return NotImplemented
        return self.nanoseconds == other.nanoseconds

    def __hash__(self) -> int:
        return hash(self.nanoseconds)

    def __lt__(self, other: Duration) -> bool:
        if not isinstance(other, Duration):
            return NotImplemented
        return self.nanoseconds < other.nanoseconds

    def __add__(self, other: Duration) -> Duration:
        if not isinstance(other, Duration):
            return NotImplemented
        return Duration(nanoseconds=self.nanoseconds + other.nanoseconds)

    def __sub__(self, other: Duration) -> Duration:
        if not isinstance(other, Duration):
            return NotImplemented
        return Duration(nanoseconds=self.nanoseconds - other.nanoseconds)

    def __mul__(self, factor: float) -> Duration:
        return Duration(nanoseconds=round(self.nanoseconds * factor))

    __rmul__ = __mul__
