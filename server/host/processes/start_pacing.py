"""How many node processes may start at once on this server. A start is admitted into one of a
few slots, each held for about as long as a node process takes to import its libraries and join;
a start that finds every slot held is told the time of its turn, after the starts told to come
back before it. Two kinds of start ask: ``GET /api/zenoh/join?start=true`` (a node process about
to start, as ``ros2lab run`` asks; api/routes/lab.py answers a deferred one 429 with
``Retry-After``, and ``ros2lab run`` waits that long and asks again), and, where the server
serves others, a student's node the page's Run or Launch starts (server/services/launch/launcher.py
keeps it waiting, then starts it at its turn). A join without ``start`` (``ros2lab env``, a tool
reading the router) is never paced. A server process has one pacer: its cores are shared. A
class server and the world workers it starts on its own machine share one too
(``MachineStartPacer``): the machine's slots, kept in one small file they all lock, not a set per
process (a class spread over an 8-core machine would otherwise start 8 × 7 nodes at once).

Why: a node's start is a burst of CPU (the interpreter, rclpy, the messages, the Zenoh session).
Sixty of them at once on a 2-core class server (a class told "run it now") share the cores with
the worlds' loops, and the scheduler gives every runnable process its share: the worlds fell
behind and a page's WebSocket handshake waited over 10 s. Paced, at most ``slots`` starts share
the cores with the server at any moment, and a burst is all joined at about ``slots / hold_s``
starts a second.
"""

from __future__ import annotations

import fcntl
import json
import logging
import math
import os
import threading
import time
from collections.abc import Callable
from pathlib import Path

from server.base.cores import usable_cores

log = logging.getLogger(__name__)

# A handout node's sandboxed start on an idle 2-core class: about 0.25 CPU-s, 0.3 s to listed.
# 0.75 s (where 1 s was set for starts of 0.5 CPU-s) joined a 30-student class's 60 Runs in 51 and
# 56 s against 62 and 65 s, its worlds 5 to 10 Hz lower while they started (docs/performance.md).
HOLD_S = 0.75
GRACE = 0.25  # of hold_s: see StartPacer._admit
BUSY_WAIT_S = 0.05  # the machine's slots file locked by another process now: ask again this soon


def machine_slots_file(state_dir: Path) -> Path:
    """Where a class server keeps its machine's start slots, shared with the world workers it
    starts here (they are told this path)."""
    return state_dir / "start-slots"


def default_slots() -> int:
    """One start at a time per core the server does not need (at least one; the cores it may use,
    as its affinity and CPU quota allow)."""
    return max(1, usable_cores() - 1)


class StartPacer:
    """At most ``slots`` starts admitted within any ``hold_s``; ``clock`` is injected for tests."""

    def __init__(
        self, slots: int, hold_s: float = HOLD_S, clock: Callable[[], float] = time.monotonic
    ) -> None:
        if slots < 1 or hold_s <= 0:
            raise ValueError(f"a start pacer needs slots >= 1 and hold_s > 0, got {slots} and {hold_s}")
        self.slots, self.hold_s, self._clock = slots, hold_s, clock
        self._held: list[float] = []  # when each held slot frees, oldest first
        self._last_turn = -math.inf  # the latest time a deferred start was told to come back at
        self.admitted = 0
        self.deferred = 0
        self._lock = threading.Lock()  # the API's joins and the launcher's starts may ask at once

    def admit(self) -> float | None:
        """None if this start may go ahead now (it holds a slot), else seconds until its turn: when
        the first slot frees, and after every start told to come back before it (one slot's share
        of ``hold_s`` apart), so each waiting start asks again about once rather than every time a
        slot might have freed."""
        with self._lock:
            return self._admit(self._clock())

    def _admit(self, now: float) -> float | None:
        # A slot that frees within a quarter of ``hold_s`` counts as free. The start ahead may have
        # been admitted a little late, so its slot frees a little after the next start's turn: that
        # start goes at its turn, not to the back of the line (60 paced starts took 104 s so).
        self._held = [t for t in self._held if t > now + self.hold_s * GRACE]
        if len(self._held) < self.slots:
            self._held.append(now + self.hold_s)
            self.admitted += 1
            return None
        self.deferred += 1
        self._last_turn = max(self._held[0], self._last_turn + self.hold_s / self.slots)
        return self._last_turn - now


class MachineStartPacer(StartPacer):
    """A ``StartPacer`` whose slots every process on this machine that names the same ``path``
    shares: the held slots and the latest turn live in that file, read and written under an
    exclusive ``flock``. The clock must be the machine's (``time.monotonic``: the same in every
    process of one boot), as a time in the file is read by the others.

    It never blocks its caller (the server's event loop): a lock another process holds at that
    instant defers the start by ``BUSY_WAIT_S``, and a file it cannot open or read paces this
    process alone, as a ``StartPacer`` does (logged once)."""

    def __init__(
        self, path: Path, slots: int, hold_s: float = HOLD_S, clock: Callable[[], float] = time.monotonic
    ) -> None:
        super().__init__(slots, hold_s, clock)
        self.path = path
        self._alone = False  # the file failed once: this process paces itself from then on

    def admit(self) -> float | None:
        with self._lock:
            now = self._clock()
            if self._alone:
                return self._admit(now)
            try:
                return self._admit_shared(now)
            except OSError as exc:
                self._alone = True
                log.warning(
                    "node starts paced by this process alone: the slots file %s failed: %s", self.path, exc
                )
                return self._admit(now)

    def _admit_shared(self, now: float) -> float | None:
        self.path.parent.mkdir(parents=True, exist_ok=True)
        fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o600)
        try:
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                self.deferred += 1
                return BUSY_WAIT_S
            self._held, self._last_turn = _read_slots(fd)
            wait_s = self._admit(now)
            last = None if math.isinf(self._last_turn) else self._last_turn
            text = json.dumps({"boot": BOOT_ID, "held": self._held, "last_turn": last})
            os.lseek(fd, 0, os.SEEK_SET)
            os.ftruncate(fd, 0)
            os.write(fd, text.encode())
            return wait_s
        finally:
            os.close(fd)  # and with it the lock


def _boot_id() -> str:
    """This boot's id (Linux): times on the monotonic clock compare only within one boot."""
    try:
        return Path("/proc/sys/kernel/random/boot_id").read_text().strip()
    except OSError:
        return ""


BOOT_ID = _boot_id()


def _read_slots(fd: int) -> tuple[list[float], float]:
    """The held slots and the latest turn a slots file holds; none (a fresh state) where it is
    empty, not what this module writes, or written in another boot."""
    try:
        data = json.loads(os.pread(fd, 65536, 0) or b"{}")
        held = sorted(float(t) for t in data["held"])
        last = -math.inf if data["last_turn"] is None else float(data["last_turn"])
        if data["boot"] != BOOT_ID or not all(math.isfinite(t) for t in [*held, max(last, 0.0)]):
            return [], -math.inf
        return held, last
    except (ValueError, TypeError, KeyError, AttributeError):
        return [], -math.inf
