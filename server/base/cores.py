"""The cores this process may use: what a class server weighs its machine by (its start slots,
the world workers it starts beside itself, its world budget), read the way a container limits it."""

from __future__ import annotations

import math
import os
from pathlib import Path

_CPU_MAX = Path("/sys/fs/cgroup/cpu.max")


def usable_cores(cpu_max: Path = _CPU_MAX) -> int:
    """The cores this process may use: those its CPU affinity allows (a container's cpuset), or
    fewer when its cgroup's CPU quota is less (cgroup v2's ``cpu.max``, as a container's
    ``--cpus`` or a pod's CPU limit sets it; 1.5 cores' worth counts as 2). A machine without
    the file, or a quota of ``max``, leaves the affinity."""
    try:
        cores = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):  # no affinity on this platform
        cores = os.cpu_count() or 1
    try:
        quota, period = cpu_max.read_text().split()[:2]
        if quota != "max" and int(period) > 0 and int(quota) > 0:
            cores = min(cores, math.ceil(int(quota) / int(period)))
    except (OSError, ValueError):
        pass  # no cgroup v2 here, or a file of another shape: the affinity stands
    return cores
