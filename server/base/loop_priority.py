"""The world loop's thread in the kernel's real-time scheduling class, where the machine allows it.

A lab's worlds tick on one event loop, in one thread. Beside other busy processes (a class's node
processes, the pages' clients, the other world loop) the kernel's fair scheduler lets a thread that
wakes run at once only while the scheduler owes it time, and a world loop, the heaviest thread on
the machine, seldom is owed: in a class of 30 on two cores each loop waited for a core 26 to 62 ms
of every second and its worlds' ticks ran 4 to 7 ms late at p99 (docs/performance.md). In the
real-time class (``SCHED_RR`` at its lowest priority, 1) a loop runs as soon as it wakes, before
any thread of the fair class; there the same loops waited under 1 ms a second.

Only the loop's thread. The class is taken with ``SCHED_RESET_ON_FORK``, so every thread and
process started from that thread afterwards begins in the fair class at niceness 0: Zenoh's and
viser's threads, asyncio's workers, a world worker, a student's node and its sandbox. What a
student runs never inherits it, and a sandboxed node cannot take it (its RLIMIT_RTPRIO is 0:
node_runtime/process/confinement.py). Whatever the real-time threads do, the kernel keeps 5 % of
every second for the rest (``/proc/sys/kernel/sched_rt_runtime_us``), and a loop is one thread, so
at most one core.

Taking it needs ``CAP_SYS_NICE`` (root, or a container given it) or an ``RLIMIT_RTPRIO`` of 1 or
more (``ulimit -r 1``). Without either the loop stays in the fair class and the outcome says why.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Literal

Scheduling = Literal["realtime", "normal"]
SCHEDULINGS: tuple[Scheduling, ...] = ("realtime", "normal")
REALTIME_PRIORITY = 1  # the lowest of SCHED_RR's: any real-time thread the machine has goes first
NOT_PERMITTED = "not permitted: it needs CAP_SYS_NICE or an RLIMIT_RTPRIO of 1 or more (ulimit -r 1)"


@dataclass(frozen=True)
class LoopPriority:
    """What the loop's thread runs at, and why (one line, for the console)."""

    scheduling: Scheduling
    why: str

    def line(self) -> str:
        if self.scheduling == "realtime":
            return f"world loop: real-time priority ({self.why})"
        return f"world loop: normal priority ({self.why})"


def scheduling_of(thread_id: int) -> Scheduling | None:
    """The scheduling class of the thread ``thread_id`` (a native id; 0: the calling thread), None
    where it cannot be read (a thread gone, a system without the call)."""
    try:
        policy = os.sched_getscheduler(thread_id) & ~os.SCHED_RESET_ON_FORK
    except (OSError, AttributeError):
        return None
    return "realtime" if policy in (os.SCHED_RR, os.SCHED_FIFO) else "normal"


@contextlib.contextmanager
def loop_priority(wanted: Scheduling) -> Iterator[LoopPriority]:
    """The calling thread in the real-time class while the block runs, when ``wanted`` and the
    machine allows it; its own class and priority again after."""
    if wanted == "normal":
        yield LoopPriority("normal", "--loop-priority normal")
        return
    try:
        before = os.sched_getscheduler(0), os.sched_getparam(0)
        os.sched_setscheduler(0, os.SCHED_RR | os.SCHED_RESET_ON_FORK, os.sched_param(REALTIME_PRIORITY))
    except PermissionError:
        yield LoopPriority("normal", NOT_PERMITTED)
        return
    except (OSError, AttributeError) as exc:  # no such call here, or the kernel refused the class
        yield LoopPriority("normal", f"the system refused it: {exc}")
        return
    try:
        yield LoopPriority("realtime", f"SCHED_RR {REALTIME_PRIORITY}, not passed to what it starts")
    finally:
        with contextlib.suppress(OSError):  # a thread may always leave the real-time class
            os.sched_setscheduler(0, *before)
