"""``ros2lab run`` against a lab that serves others (with a token: a class's world, or a lab beyond
loopback) runs its node below that lab's worlds, at the niceness the lab's join names (its
sandbox's, 19 unless set; node_runtime/process/priority.py gives the node's session group the same).

A class told "run it now" starts twenty commands at once, and on the server's own machine (students
in terminals there) each imports its HTTP client and the verb's modules, about half a second of
CPU, before it can ask the lab anything. At the worlds' priority those imports alone held the
worlds' loop back for seconds. So with a token the command takes ``START_NICE`` before it imports
them, and its node then goes lower still if the join names more. A niceness cannot be taken back
without privileges: against a lab on loopback behind a token, whose join names none, the node runs
at ``START_NICE`` all the same.
"""

from __future__ import annotations

import os

START_NICE = 19  # the sandbox's default (server/host/settings/): the lowest
_started_at: int | None = None  # the command's own niceness before START_NICE (None: not taken)


def start_below_the_worlds() -> None:
    """Take ``START_NICE`` now, before the command's imports."""
    global _started_at
    _started_at = os.getpriority(os.PRIO_PROCESS, 0)
    os.nice(START_NICE)


def take_the_labs_nice(nice: int) -> None:
    """At least ``nice`` below the niceness the command started with (part of it may be taken)."""
    now = os.getpriority(os.PRIO_PROCESS, 0)
    start = _started_at if _started_at is not None else now
    if start + nice > now:
        os.nice(start + nice - now)
