"""How busy a process and its machine are: what a world worker's hello reports, and what the class
server weighs before it places a new world on the place with the most room.

- ``process_cores``: the CPU time this process used (every thread) over the last window, in cores.
  A process's worlds share one event loop, in one Python thread, so near one core it is full
  however many cores the machine has.
- ``rss_mb``: the process's resident memory now, in MiB, from ``/proc/self/statm`` (None without it).
- ``loop``: the scheduling class of the process's worlds' loop thread, "realtime" or "normal"
  (server/base/loop_priority.py; None where it cannot be read).
- ``host_busy``: the share of the machine's CPU time that was busy over the window, for every
  process, from ``/proc/stat``. Time the hypervisor stole counts as busy: it is capacity this
  machine did not have. None where ``/proc/stat`` is missing.

A place is *saturated* when its process uses ``PROCESS_FULL_CORES`` or its machine is
``HOST_FULL`` busy. Placement goes by worlds against capacity, and never to a full process while
another place has room; a busy machine counts against its places only when a place on another
machine is in the choice, since places on one machine share its CPU (``choose``, docs/classroom.md).
"""

from __future__ import annotations

import hashlib
import os
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Generic, TypeVar

from server.base.cores import usable_cores
from server.base.loop_priority import SCHEDULINGS, Scheduling, scheduling_of

Ref = TypeVar("Ref")  # who a place is (placement's WorkerRef); this module needs only its identity

PROCESS_FULL_CORES = 0.85  # a process's worlds share one loop thread: near one core it is full
HOST_FULL = 0.90  # the machine's share of CPU time busy (steal included)
MIN_WINDOW_S = 1.0  # a load is measured over at least this long; reads in between repeat it
_PROC_STAT = Path("/proc/stat")


def host_times() -> tuple[int, int] | None:
    """(busy, total) CPU ticks of the whole machine since boot, or None without ``/proc/stat``.
    Busy is everything but idle and iowait: user, nice, system, irq, softirq and steal."""
    try:
        first = _PROC_STAT.read_text().split("\n", 1)[0].split()
    except OSError:
        return None
    if not first or first[0] != "cpu" or len(first) < 5:
        return None
    ticks = [int(v) for v in first[1:9]]  # guest time is already inside user and nice
    idle = ticks[3] + (ticks[4] if len(ticks) > 4 else 0)
    total = sum(ticks)
    return total - idle, total


@dataclass(frozen=True)
class CpuLoad:
    process_cores: float
    host_busy: float | None
    cores: int
    machine: str | None = None  # which machine (a digest of its boot id): places on one share its CPU
    rss_mb: float | None = None  # the process's resident memory (MiB); None where not known
    loop: Scheduling | None = None  # its worlds' loop thread's scheduling class; None where not known

    @property
    def process_full(self) -> bool:
        return self.process_cores >= PROCESS_FULL_CORES

    @property
    def host_full(self) -> bool:
        return self.host_busy is not None and self.host_busy >= HOST_FULL

    @property
    def saturated(self) -> bool:
        return self.process_full or self.host_full

    def describe(self) -> dict[str, Any]:
        return {
            "process_cores": round(self.process_cores, 3),
            "host_busy": None if self.host_busy is None else round(self.host_busy, 3),
            "cores": self.cores,
            "machine": self.machine,
            "rss_mb": None if self.rss_mb is None else round(self.rss_mb, 1),
            "loop": self.loop,
            "saturated": self.saturated,
        }

    @classmethod
    def parse(cls, body: object) -> CpuLoad | None:
        """A load as a hello carried it, or None for anything else (a hello is untrusted shape)."""
        if not isinstance(body, dict):
            return None
        process, host, cores = body.get("process_cores"), body.get("host_busy"), body.get("cores")
        machine = body.get("machine")
        if not isinstance(process, int | float) or isinstance(process, bool) or not 0 <= process < 1e6:
            return None
        if host is not None and (
            not isinstance(host, int | float) or isinstance(host, bool) or not 0 <= host <= 1
        ):
            return None
        if not isinstance(cores, int) or isinstance(cores, bool) or cores < 1:
            return None
        if machine is not None and (not isinstance(machine, str) or not 0 < len(machine) <= 64):
            return None
        rss = body.get("rss_mb")
        if rss is not None and (
            not isinstance(rss, int | float) or isinstance(rss, bool) or not 0 <= rss < 1e9
        ):
            rss = None  # an older worker's hello, or a garbled one: the CPU still counts
        loop = body.get("loop")
        return cls(
            float(process),
            None if host is None else float(host),
            cores,
            machine,
            None if rss is None else float(rss),
            next((s for s in SCHEDULINGS if s == loop), None),
        )


def machine_id() -> str | None:
    """A digest of this boot's id: the same for every process (and container) on one machine."""
    try:
        boot = Path("/proc/sys/kernel/random/boot_id").read_text().strip()
    except OSError:
        return None
    return hashlib.sha256(f"ros2lab-machine/{boot}".encode()).hexdigest()[:16] if boot else None


def resident_mb() -> float | None:
    """This process's resident memory in MiB, or None without ``/proc/self/statm``."""
    try:
        pages = int(Path("/proc/self/statm").read_text().split()[1])
    except (OSError, IndexError, ValueError):
        return None
    return pages * os.sysconf("SC_PAGE_SIZE") / 2**20


class CpuMeter:
    """This process's and its machine's CPU over the last window of at least ``MIN_WINDOW_S``, and
    the scheduling class of ``loop_thread`` (a native thread id; by default the thread that makes
    the meter, as the class server and a world worker make theirs on their loop's thread).
    Thread-safe: a worker reads it on Zenoh's thread, the class server on its loop."""

    def __init__(
        self,
        now: Callable[[], float] = time.monotonic,
        process_time: Callable[[], float] = time.process_time,
        host: Callable[[], tuple[int, int] | None] = host_times,
        cores: int | None = None,
        machine: str | None = None,
        rss: Callable[[], float | None] = resident_mb,
        loop_thread: int | None = None,
    ) -> None:
        self._now, self._process_time, self._host, self._rss = now, process_time, host, rss
        self.loop_thread = threading.get_native_id() if loop_thread is None else loop_thread
        self.cores = cores if cores is not None else usable_cores()
        self.machine = machine
        self._lock = threading.Lock()
        self._mark = (now(), process_time(), host())
        self._load = CpuLoad(0.0, None, self.cores, machine, rss(), scheduling_of(self.loop_thread))

    def read(self) -> CpuLoad:
        with self._lock:
            now = self._now()
            then, cpu_then, host_then = self._mark
            elapsed = now - then
            if elapsed < MIN_WINDOW_S:
                return self._load
            cpu, host = self._process_time(), self._host()
            busy: float | None = None
            if host is not None and host_then is not None and host[1] > host_then[1]:
                busy = min(1.0, max(0.0, (host[0] - host_then[0]) / (host[1] - host_then[1])))
            cores = max(0.0, cpu - cpu_then) / elapsed
            loop = scheduling_of(self.loop_thread)
            self._load = CpuLoad(cores, busy, self.cores, self.machine, self._rss(), loop)
            self._mark = (now, cpu, host)
            return self._load


@dataclass(frozen=True)
class Choice(Generic[Ref]):
    """A place a new world could go: its worlds over its capacity, who (None: the class server
    itself) and its CPU, if known."""

    share: float
    ref: Ref | None  # None: the class server itself
    load: CpuLoad | None


def choose(choices: list[Choice[Ref]]) -> tuple[Choice[Ref], bool]:
    """The place with the lowest share among those not full (all of them if every one is), and
    whether it is full; on a tie a worker before the class server, then the order given. A place
    is full when its process is; its machine being busy counts only when another machine is in
    the choice, since places on one machine share its CPU wherever the world goes."""
    if not choices:
        raise ValueError("no place to choose from")
    machines = {c.load.machine for c in choices if c.load is not None}

    def full(c: Choice[Ref]) -> bool:
        if c.load is None:
            return False
        return c.load.process_full or (c.load.host_full and len(machines) > 1)

    best = min(choices, key=lambda c: (full(c), c.share, c.ref is None))
    return best, full(best)
