"""``ros2 topic hz``: statistics of the periods between a topic's messages, and percentiles."""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from itertools import islice, pairwise


@dataclass(frozen=True)
class RateStats:
    """Statistics of the periods between consecutive messages, as ``ros2 topic hz`` prints them.

    ``window`` is how many periods were used; with none, every other field is None. ``rate_hz``
    is 1 / mean period (None when the mean is 0: every message at one instant). ``std_dev_s`` is
    the population standard deviation, as ros2 computes it.
    """

    window: int
    rate_hz: float | None = None
    min_s: float | None = None
    max_s: float | None = None
    std_dev_s: float | None = None


def rate_stats(times_s: Sequence[float], window: int) -> RateStats:
    """Rate over the last ``window`` periods, i.e. between the last ``window + 1`` of ``times_s``."""
    if window < 1:
        raise ValueError(f"window must be at least 1 period, got {window}")
    start = max(0, len(times_s) - (window + 1))
    recent = list(islice(times_s, start, None))
    periods = [b - a for a, b in pairwise(recent)]
    if not periods:
        return RateStats(window=0)
    mean = sum(periods) / len(periods)
    std = math.sqrt(sum((p - mean) ** 2 for p in periods) / len(periods))
    return RateStats(
        window=len(periods), rate_hz=1.0 / mean if mean > 0 else None,
        min_s=min(periods), max_s=max(periods), std_dev_s=std,
    )  # fmt: skip


def percentile(values: Iterable[float], q: float) -> float | None:
    """The ``q``-th percentile (0..100), linearly interpolated as numpy's default; None if empty."""
    data = sorted(values)
    if not data:
        return None
    pos = (len(data) - 1) * q / 100.0
    lo = math.floor(pos)
    hi = min(lo + 1, len(data) - 1)
    return data[lo] + (data[hi] - data[lo]) * (pos - lo)
