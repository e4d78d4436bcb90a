"""Injectable time: a monotonic clock for the running app, a manual clock for tests."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Protocol

from node_runtime.msgs import Time as TimeMsg


class Clock(Protocol):
    def now(self) -> float:
        """Seconds; monotonic, never going back."""
        ...


class SystemClock:
    """Monotonic time shifted to the Unix epoch, so stamps read as wall time but never jump."""

    def __init__(self) -> None:
        self._offset = time.time() - time.monotonic()

    def now(self) -> float:
        return time.monotonic() + self._offset


class ManualClock:
    """Time that moves only when a test moves it."""

    def __init__(self, start_s: float = 0.0) -> None:
        self._now = float(start_s)

    def now(self) -> float:
        return self._now

    def set(self, t_s: float) -> None:
        if t_s < self._now:
            raise ValueError(f"a clock must not go back ({t_s} < {self._now})")
        self._now = float(t_s)

    def advance(self, dt_s: float) -> None:
        self.set(self._now + dt_s)


@dataclass(frozen=True)
class RosTime:
    """rclpy's Time: ``node.get_clock().now().to_msg()`` works as in ROS."""

    nanoseconds: int

    @classmethod
    def from_seconds(cls, t_s: float) -> RosTime:
        # Split first: epoch seconds * 1e9 needs more than a double's 53 bits and would lose nanoseconds.
        sec = math.floor(t_s)
        return cls(sec * 1_000_000_000 + round((t_s - sec) * 1e9))

    def to_msg(self) -> TimeMsg:
        sec, nanosec = divmod(self.nanoseconds, 1_000_000_000)
        return TimeMsg(sec=sec, nanosec=nanosec)

    def seconds_nanoseconds(self) -> tuple[int, int]:
        sec, nanosec = divmod(self.nanoseconds, 1_000_000_000)
        return sec, nanosec


class NodeClock:
    """What ``node.get_clock()`` returns."""

    def __init__(self, clock: Clock) -> None:
        self._clock = clock

    def now(self) -> RosTime:
        return RosTime.from_seconds(self._clock.now())
