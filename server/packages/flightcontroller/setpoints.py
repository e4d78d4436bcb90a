"""What counts as a sane setpoint: the lab's arena, and the line between "clamp it" and "refuse it"."""

from __future__ import annotations

import math
from collections.abc import Sequence

ARENA_MIN_M = (-10.0, -10.0, 0.0)  # the lab's view: x, y in [-10, 10], z in [0, 15]
ARENA_MAX_M = (10.0, 10.0, 15.0)
ABSURD_M = 1e4  # beyond this a value is a mistake, not a far-away goal: refused, not clamped
MAX_SPEED_SETPOINT_M_S = 20.0


class SetpointError(ValueError):
    """A setpoint that must be dropped (NaN, infinity, absurd magnitude)."""


def check_finite(values: Sequence[float], what: str, limit: float = ABSURD_M) -> tuple[float, float, float]:
    x, y, z = (float(v) for v in values)
    for axis, v in zip("xyz", (x, y, z), strict=True):
        if not math.isfinite(v):
            raise SetpointError(f"{what}.{axis} is {v}: not a finite number")
        if abs(v) > limit:
            raise SetpointError(f"{what}.{axis} = {v:g} is absurd (|value| > {limit:g})")
    return x, y, z


def clamp_to_arena(position_m: Sequence[float]) -> tuple[tuple[float, float, float], bool]:
    """The position clamped into the arena, and whether it had to be."""
    clamped = tuple(
        min(max(v, lo), hi) for v, lo, hi in zip(position_m, ARENA_MIN_M, ARENA_MAX_M, strict=True)
    )
    return (clamped[0], clamped[1], clamped[2]), clamped != tuple(position_m)
