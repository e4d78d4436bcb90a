"""Whole fixed-rate steps for a span of simulated time, the part short of a step carried over."""

from __future__ import annotations

import math
from collections.abc import Callable


class FixedStepClock:
    """Turns durations into whole steps of 1/rate_hz; the remainder carries over to the next call."""

    def __init__(self, rate_hz: float) -> None:
        self.rate_hz = float(rate_hz)
        self.dt_s = 1.0 / self.rate_hz
        self._remainder_s = 0.0

    def steps_for(self, duration_s: float) -> int:
        """Whole steps due after duration_s more seconds; ValueError unless finite and >= 0."""
        if not (math.isfinite(duration_s) and duration_s >= 0.0):
            raise ValueError(f"duration_s must be finite and >= 0, got {duration_s}")
        total = self._remainder_s + duration_s
        # The epsilon absorbs rounding so that 0.02 s at 1 kHz is 20 steps, not 19.
        n = math.floor(total * self.rate_hz + 1e-6)
        self._remainder_s = max(0.0, total - n * self.dt_s)
        return n

    def run(self, duration_s: float, step: Callable[[], object]) -> int:
        """Call step once per whole step due after duration_s more seconds; returns how many."""
        n = self.steps_for(duration_s)
        for _ in range(n):
            step()
        return n

    def reset(self) -> None:
        """Forget the carried remainder."""
        self._remainder_s = 0.0
