"""One frame's history: where it was in its parent over time (tf2's TimeCache), or for all time
(its StaticCache, for /tf_static).

Times are integer nanoseconds since the epoch; 0 asks for the latest. A time between two stored
records is interpolated; one outside them is an ``ExtrapolationException`` with tf2's wording.
"""

from __future__ import annotations

import bisect
from dataclasses import dataclass

import numpy as np

from tf2_ros._exceptions import ExtrapolationException
from tf2_ros._transform_math import RigidTransform, interpolate

NS_PER_S = 1_000_000_000
DEFAULT_CACHE_TIME_NS = 10 * NS_PER_S  # tf2's BUFFER_CORE_DEFAULT_CACHE_TIME


def seconds_text(stamp_ns: int) -> str:
    """A time as tf2 prints one in its messages: seconds with six decimals."""
    return f"{stamp_ns / NS_PER_S:.6f}"


@dataclass(frozen=True)
class Record:
    """The child frame's place in ``parent`` at ``stamp_ns``."""

    stamp_ns: int
    parent: str
    transform: RigidTransform

    def same_as(self, other: Record) -> bool:
        return (
            self.stamp_ns == other.stamp_ns
            and self.parent == other.parent
            and np.array_equal(self.transform.translation, other.transform.translation)
            and np.array_equal(self.transform.rotation, other.transform.rotation)
        )


class TimeCache:
    """Records of a moving frame, oldest first, kept for ``cache_time_ns`` behind the newest."""

    def __init__(self, cache_time_ns: int = DEFAULT_CACHE_TIME_NS) -> None:
        self.cache_time_ns = cache_time_ns
        self._records: list[Record] = []
        self._stamps: list[int] = []

    def insert(self, record: Record) -> bool:
        """Keep ``record``; False (and nothing kept) when it is older than the cache reaches."""
        self._prune()
        if self._records and record.stamp_ns < self._stamps[-1] - self.cache_time_ns:
            return False
        at = bisect.bisect_right(self._stamps, record.stamp_ns)
        same_stamp = range(bisect.bisect_left(self._stamps, record.stamp_ns), at)
        if any(self._records[i].same_as(record) for i in same_stamp):
            return True  # a repeat (a re-sent message): nothing new
        self._records.insert(at, record)
        self._stamps.insert(at, record.stamp_ns)
        return True

    def _prune(self) -> None:
        if not self._records:
            return
        keep_from = bisect.bisect_left(self._stamps, self._stamps[-1] - self.cache_time_ns)
        del self._records[:keep_from]
        del self._stamps[:keep_from]

    def clear(self) -> None:
        self._records.clear()
        self._stamps.clear()

    def _closest(self, time_ns: int) -> tuple[Record, Record | None]:
        """The record at ``time_ns``, or the two around it (older, newer); raises when there are none."""
        if not self._records:
            raise ExtrapolationException(
                f"Lookup would require extrapolation at time {seconds_text(time_ns)}, "
                f"but only time {seconds_text(0)} is in the buffer"
            )
        if time_ns == 0:
            return self._records[-1], None
        if len(self._records) == 1:
            only = self._records[0]
            if only.stamp_ns == time_ns:
                return only, None
            raise ExtrapolationException(
                f"Lookup would require extrapolation at time {seconds_text(time_ns)}, "
                f"but only time {seconds_text(only.stamp_ns)} is in the buffer"
            )
        oldest, newest = self._stamps[0], self._stamps[-1]
        if time_ns > newest:
            raise ExtrapolationException(
                "Lookup would require extrapolation into the future.  Requested time "
                f"{seconds_text(time_ns)} but the latest data is at time {seconds_text(newest)}"
            )
        if time_ns < oldest:
            raise ExtrapolationException(
                "Lookup would require extrapolation into the past.  Requested time "
                f"{seconds_text(time_ns)} but the earliest data is at time {seconds_text(oldest)}"
            )
        if time_ns == newest:
            return self._records[-1], None
        newer = bisect.bisect_right(self._stamps, time_ns)
        older = self._records[newer - 1]
        if older.stamp_ns == time_ns:
            return older, None
        return older, self._records[newer]

    def parent_at(self, time_ns: int) -> str:
        return self._closest(time_ns)[0].parent

    def at(self, time_ns: int) -> Record:
        """The frame's place at ``time_ns``, interpolated between the records around it when both
        name the same parent (else the older one's, as tf2 does)."""
        older, newer = self._closest(time_ns)
        if newer is None or newer.parent != older.parent:
            return older
        ratio = (time_ns - older.stamp_ns) / (newer.stamp_ns - older.stamp_ns)
        return Record(time_ns, older.parent, interpolate(older.transform, newer.transform, ratio))

    def latest(self) -> tuple[int, str] | None:
        """The newest record's stamp and parent; None when there is none."""
        if not self._records:
            return None
        return self._records[-1].stamp_ns, self._records[-1].parent

    @property
    def newest_ns(self) -> int:
        return self._stamps[-1] if self._stamps else 0

    @property
    def oldest_ns(self) -> int:
        return self._stamps[0] if self._stamps else 0

    def __len__(self) -> int:
        return len(self._records)


class StaticCache:
    """A frame fixed in its parent for all time: one record, whatever the time asked."""

    def __init__(self, record: Record) -> None:
        self._record = record

    def insert(self, record: Record) -> bool:
        self._record = record
        return True

    def clear(self) -> None:
        """Static frames outlive a buffer's ``clear()``, as in tf2."""

    def parent_at(self, time_ns: int) -> str:
        return self._record.parent

    def at(self, time_ns: int) -> Record:
        return Record(time_ns, self._record.parent, self._record.transform)

    def latest(self) -> tuple[int, str] | None:
        return 0, self._record.parent  # 0: no time of its own, it never limits a common time

    newest_ns = 0
    oldest_ns = 0

    def __len__(self) -> int:
        return 1


FrameCache = TimeCache | StaticCache
