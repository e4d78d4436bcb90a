"""Whether a world keeps its time, and how many of its timers' calls a process's worlds skipped.

A world is *late* when one of its timers (its dynamics' tick, its controller's, its sensors') ran
more than ``LATE_TICK_S`` after its deadline, as a median over its last ``RECENT_TICKS`` calls (a
timer with fewer calls than that has just started, and its first ticks waited for its world's
start: not judged yet), or its next call is ``STALLED_S`` overdue now (its loop is stalled: what a
world worker's hello, answered on Zenoh's thread, can see). The overdue bound is longer than a
late tick's because a class server reads it on the loop itself, right after a join's world start
held that loop for a moment: its timers have not caught up yet, though they will on the next pass.

The lab already keeps every timer's lateness (``Timer.lateness_s``, what ``ros2 node info``
shows as percentiles); this reads its newest samples, so the window is each timer's last few
ticks, not a clock of its own.

``SkippedCalls`` reads how many calls the timers of a process's worlds skipped lately, as a share
of the calls due (a call a whole period late skips the calls due meanwhile, as the timer keeps
its phase: a 100 Hz tick skipped once a second is a world at 99 Hz); the process's node starts
yield to it (server/host/processes/start_pacing.py).
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable
from statistics import median

from node_runtime.bus import Bus, Timer
from server.world.lab import Lab

LATE_TICK_S = 0.05  # a 20 Hz timer (the slowest tick of the handout's nodes) skips a call past this
RECENT_TICKS = 20
STALLED_S = 1.0  # a next call this overdue: the loop is stalled, not just busy for a moment
SKIPPED_WINDOW_S = 0.5  # the calls skipped are counted over at least this long


def timer_late(timer: Timer, now_s: float) -> bool:
    """A timer is late when its recent calls ran late, or its next call is stalled now."""
    count = len(timer.lateness_s)
    if timer.cancelled or not count:  # not yet called: its world is still starting
        return False
    if now_s - timer.next_deadline_s > STALLED_S:
        return True
    if count < RECENT_TICKS:  # a world just started: its first ticks waited for the start to end
        return False
    recent = [timer.lateness_s[i] for i in range(max(0, count - RECENT_TICKS), count)]
    return median(recent) > LATE_TICK_S


def timers_late(timers: Iterable[Timer], now_s: float) -> bool:
    return any(timer_late(t, now_s) for t in timers)


def world_late(lab: Lab) -> bool:
    """Whether any active node of ``lab`` has a late timer."""
    now_s = lab.bus.clock.now()
    return any(timers_late(node.timers, now_s) for node in lab.bus.nodes if node.state == "active")


def late_worlds(labs: Iterable[Lab | None]) -> int:
    """How many of these labs are late (a world running elsewhere, None, is not counted here)."""
    return sum(1 for lab in labs if lab is not None and world_late(lab))


class SkippedCalls:
    """The share of the calls due to the timers of ``buses`` (a process's worlds) that they skipped
    since the reading before, taken at most every ``window_s`` (a reading sooner gives the last
    share again). A bus is counted from its first reading on: a world that has just started (whose
    first ticks waited for its start) or has gone changes nothing."""

    def __init__(
        self,
        buses: Callable[[], Iterable[Bus]],
        now: Callable[[], float] = time.monotonic,
        window_s: float = SKIPPED_WINDOW_S,
    ) -> None:
        self._buses, self._now, self.window_s = buses, now, window_s
        self._at = now()
        self._share = 0.0
        self._marks = self._counts()  # by id: each bus, its calls and those skipped then

    def _counts(self) -> dict[int, tuple[Bus, int, int]]:
        return {id(bus): (bus, bus.timer_calls, bus.timer_calls_skipped) for bus in list(self._buses())}

    def read(self) -> float:
        now = self._now()
        if now - self._at < self.window_s:
            return self._share
        counts = self._counts()
        ran = skipped = 0
        for key, (bus, calls, skips) in counts.items():
            mark = self._marks.get(key)
            if mark is not None and mark[0] is bus:
                ran += calls - mark[1]
                skipped += skips - mark[2]
        self._marks, self._at = counts, now
        due = ran + skipped
        self._share = skipped / due if due > 0 else 0.0
        return self._share
