"""Students' node processes run below the sims' loop in CPU priority, so a class's nodes starting or
spinning never make a world late.

A niceness alone is not enough on most Linux kernels: with autogroup scheduling (Debian's and
Ubuntu's default, ``/proc/sys/kernel/sched_autogroup_enabled``), every session is one group that
the scheduler weighs against the other sessions, and a process's niceness counts only against the
processes of its own session. A node in a session of its own (a sandbox: bubblewrap's
``--new-session``; ``ros2lab run``'s child) at nice 19 then still takes a full share beside the
server. Measured on a 2-core machine, two busy loops on one core, one at nice 19: in the same
session it got 1 % of the core; in a session of its own, 50 %. So the session's group gets the
same niceness (``/proc/PID/autogroup``), which only a process leading its own session may set for
itself: a node in its terminal's session leaves the terminal's other processes as they are.

A process whose session never left the system's first one (a service's, a container's) is in the
root group, and its ``/proc/PID/autogroup`` reads empty: there a niceness counts against every
process of that group, as on a kernel without autogroups.
"""

from __future__ import annotations

import os

AUTOGROUP = "/proc/{pid}/autogroup"


def set_session_group_nice(pid: int, nice: int) -> bool:
    """Give the scheduling group of ``pid``'s session the niceness ``nice`` (0 to 19); False where
    the kernel has no autogroups (nothing to set: a niceness then counts against every process)."""
    try:
        with open(AUTOGROUP.format(pid=pid), "w") as group:
            group.write(str(nice))
    except OSError:
        return False
    return True


def group_nice(line: str) -> int | None:
    """The niceness a ``/proc/PID/autogroup`` line gives (``/autogroup-42 nice 10`` → 10); None for
    the empty line of a process in the root group."""
    words = line.split()
    return int(words[-1]) if words else None


def session_group_nice(pid: int) -> int | None:
    """The niceness of ``pid``'s session group, None where it has none of its own (no autogroups,
    or the root group)."""
    try:
        with open(AUTOGROUP.format(pid=pid)) as group:
            return group_nice(group.read())
    except FileNotFoundError:
        return None


def run_below_sims(nice: int) -> None:
    """Lower this process by ``nice`` (added to its niceness, as ``nice -n``) and, if it leads its
    own session, its session's group to at least that niceness."""
    os.nice(nice)
    pid = os.getpid()
    if nice > 0 and os.getsid(0) == pid and (session_group_nice(pid) or 0) < nice:
        set_session_group_nice(pid, nice)
