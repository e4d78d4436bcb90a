"""``rclpy.timer``: ``Timer`` (what ``node.create_timer`` returns, the bus's timer with rclpy's
calls), ``TimerInfo`` (given to a callback whose parameter is annotated with it) and ``Rate``."""

from __future__ import annotations

import inspect
import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from node_runtime.bus import Timer as BusTimer
from rclpy.rate import Rate
from rclpy.time import ClockType, Time

if TYPE_CHECKING:
    from rclpy.callback_groups import CallbackGroup
    from rclpy.clock import Clock

NS_PER_S = 1_000_000_000


class TimerInfo:
    """When a timer's call was due and when it ran (``Time``s of the timer's clock)."""

    def __init__(
        self,
        *,
        expected_call_time: int = 0,
        actual_call_time: int = 0,
        clock_type: ClockType = ClockType.SYSTEM_TIME,
    ) -> None:
        if not isinstance(clock_type, ClockType):
            raise TypeError("Clock type must be a ClockType enum")
        if expected_call_time < 0 or actual_call_time < 0:
            raise ValueError("call time values must not be negative")
        self._expected = Time(nanoseconds=expected_call_time, clock_type=clock_type)
        self._actual = Time(nanoseconds=actual_call_time, clock_type=clock_type)

    @property
    def expected_call_time(self) -> Time:
        return self._expected

    @property
    def actual_call_time(self) -> Time:
        return self._actual


def _ns(t_s: float) -> int:
    sec = math.floor(t_s)
    return sec * NS_PER_S + round((t_s - sec) * 1e9)


class Timer(BusTimer):
    """Calls its callback every period on the node's clock until cancelled."""

    callback_group: CallbackGroup | None = None
    clock_source: Clock | None = None

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._last_call_s = self._start_s
        self._expected_s = self._start_s

    def advance_past(self, now_s: float) -> None:
        self._expected_s, self._last_call_s = self.next_deadline_s, now_s
        super().advance_past(now_s)

    def reset(self) -> None:
        super().reset()
        self._last_call_s = self._start_s

    @property
    def clock(self) -> Clock | None:
        return self.clock_source

    @property
    def timer_period_ns(self) -> int:
        return round(self.period_s * NS_PER_S)

    @timer_period_ns.setter
    def timer_period_ns(self, value: int) -> None:
        """A new period; the call already due stays due then, as rcl's ``change_timer_period``."""
        period_s = int(value) / NS_PER_S
        if not period_s > 0:
            raise ValueError(f"timer period must be positive, got {value} ns")
        self.period_s = period_s
        self._start_s = self.next_deadline_s - self._n * period_s

    def is_ready(self) -> bool:
        return not self.cancelled and self.node._bus.clock.now() >= self.next_deadline_s

    def time_since_last_call(self) -> int:
        """Nanoseconds since it last ran (or started)."""
        return _ns(self.node._bus.clock.now() - self._last_call_s)

    def time_until_next_call(self) -> int | None:
        """Nanoseconds until it is due (negative once overdue); None while cancelled."""
        if self.cancelled:
            return None
        return _ns(self.next_deadline_s - self.node._bus.clock.now())

    def __enter__(self) -> Timer:
        return self

    def __exit__(self, *_exc: object) -> None:
        self.destroy()

    def adapt(self, callback: Callable[..., Any] | None) -> Callable[[], Any]:
        """What the executor calls: ``callback``, given a TimerInfo by the name of its parameter
        annotated ``TimerInfo`` if it has one (as rclpy's executor looks for it)."""
        if callback is None:
            return lambda: None
        try:
            parameters = inspect.signature(callback).parameters.values()
        except (TypeError, ValueError):
            return callback
        name = next((p.name for p in parameters if p.annotation is TimerInfo), None)
        if name is None:
            return callback

        def call() -> Any:
            clock_type = self.clock_source.clock_type if self.clock_source is not None else ClockType.ROS_TIME
            info = TimerInfo(
                expected_call_time=_ns(self._expected_s),
                actual_call_time=_ns(self._last_call_s),
                clock_type=clock_type,
            )
            return callback(**{name: info})

        call.__qualname__ = getattr(callback, "__qualname__", "callback")
        return call


__all__ = ["Rate", "Timer", "TimerInfo"]
