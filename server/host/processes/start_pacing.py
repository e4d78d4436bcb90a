"""How many node processes may start at once on this server. A start is admitted into one of a
few slots, each held for about as long as a node process takes to import its libraries and join;
a start that finds every slot held is given a turn of its own, after the turns given before it,
and a ticket that keeps that turn for it: back with the ticket at its turn (or late), it goes on
the slot its turn set aside, whatever else asked meanwhile. Two kinds of start ask: ``GET
/api/zenoh/join?start=true`` (a node process about to start, as ``ros2lab run`` asks;
api/routes/lab.py answers a deferred one 429 with ``Retry-After``, the wait to the millisecond
and, asked with ``turn=new``, the ticket; ``ros2lab run`` waits that long and asks again with
``turn=TICKET``), and,
where the server serves others, a student's node the page's Run or Launch starts
(server/services/launch/launcher.py keeps it waiting, then starts it at its turn). A join without
``start`` (``ros2lab env``, a tool reading the router) is never paced. A server process has one
pacer: its cores are shared. A class server and the world workers it starts on its own machine
share one too (``MachineStartPacer``): the machine's slots and turns, kept in one small file they
all lock, not a set per process (a class spread over an 8-core machine would otherwise start
8 × 7 nodes at once).

Why: a node's start is a burst of CPU (the interpreter, rclpy, the messages, the Zenoh session).
Sixty of them at once on a 2-core class server (a class told "run it now") share the cores with
the worlds' loops, and the scheduler gives every runnable process its share: the worlds fell
behind and a page's WebSocket handshake waited over 10 s. Paced, at most ``slots`` starts share
the cores with the server at any moment, and a burst is all joined at about ``slots / hold_s``
starts a second. Why the ticket: a start told its turn comes back a little after it (HTTP's
``Retry-After`` is whole seconds, a client's timer and a busy loop are late), when the slot may
be held by a start that came back before it; without the ticket it was a new start and went to
the back of the line, and 60 ``ros2lab run`` at once took 79 and 83 s, 62 and 64 s with it.

The starts also yield to the worlds' ticks. A pacer may be told how many of the calls its
worlds' timers were due to make they skipped lately (``skipped``: a call a whole period late
skips the calls due meanwhile, as a timer keeps its phase; a class's worlds on the server: server/classroom/lateness.py).
When a start goes while more than ``SKIPPED_OK`` of them were skipped, the turns after it move
back, by up to ``MAX_STRETCH - 1`` of one start's share of ``hold_s`` at ``SKIPPED_MOST`` or
more: a class's sixty starts then take at most a tenth longer, and its worlds lose fewer of their
ticks while they start. Processes sharing a machine's slots share what they skipped too (the most
any of them skipped in the last ``SKIPPED_FRESH_S``), as the class server's worlds slow for the
starts of its world workers' nodes as much as for its own.
"""

from __future__ import annotations

import dataclasses
import fcntl
import json
import logging
import math
import os
import secrets
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from server.base.cores import usable_cores
from server.base.loop_priority import scheduling_of

log = logging.getLogger(__name__)

# A handout node's start on an idle 2-core class: about 0.2 CPU-s, 0.4 to 0.5 s from its turn to
# its node. With the worlds' loop in the real-time class (server/base/loop_priority.py) a start
# beside it no longer slows the worlds, and a slot is held about as long as a start takes: 0.5 s
# joined a 30-student class's 60 nodes in 31 to 32 s against 45 to 47 s at 0.75 s, from the page
# or by ``ros2lab run``, every world at 99.5 Hz or more while they started (docs/performance.md).
HOLD_S = 0.5
# Where the loop stays in the fair class (an ordinary user's laptop, a pod without the capability)
# the starts slow the worlds, and a slot is held longer: 0.75 s joined the same class's 60 Runs in
# 51 and 56 s against 62 and 65 s at 1 s, its worlds 5 to 10 Hz lower while they started.
FAIR_LOOP_HOLD_S = 0.75
GRACE = 0.25  # of hold_s: see StartPacer._admit
BUSY_WAIT_S = 0.05  # the machine's slots file locked by another process now: ask again this soon
KEPT_S = 5.0  # a turn is kept this long past its time for its start to come back, then given up
MAX_TURNS = 256  # turns kept at once; past them a start is told its wait with no ticket
# Turns one world (or one lab's user) may wait for at once. Past them its starts are told when
# the line ends and are given no turn: a student asking to start in a loop can then push the
# class's other starts back by this many turns at most, not by one turn for every ask.
MAX_WAITING = 8
TICKET_CHARS = 64  # a ticket is shorter: anything longer is not one (the API refuses it)
NEW_TURN = "new"  # asked with instead of a ticket: a start that will come back with the one it is given
# The worlds' skipped timer calls, as a share of those due, under which starts go at their full
# pace, and from which they go at their slowest: the turns then come ``MAX_STRETCH`` times as far
# apart (sixty starts in 30 s at the full pace, 33 s at the slowest). In a class's fly world about
# a third of the calls are its 100 Hz tick, which skips first (a call 10 ms late; its 50 Hz
# controllers' 20 ms): 0.5 % of every call is about 1.5 % of the ticks (a world at 98.5 Hz), 1.5 %
# about 4.5 % (95.5 Hz).
SKIPPED_OK = 0.005
SKIPPED_MOST = 0.015
MAX_STRETCH = 1.1
SKIPPED_FRESH_S = 2.0  # what another process sharing the slots skipped counts this long after it said so


@dataclass(frozen=True)
class Turn:
    """A start told to wait: ``wait_s`` until its turn, which is kept for it under ``ticket`` (None:
    none kept, for a start that keeps no ticket or past ``MAX_WAITING`` or ``MAX_TURNS``: it asks
    again as a new start)."""

    wait_s: float
    ticket: str | None = None


@dataclass(frozen=True)
class Given:
    """A turn given to a deferred start: when, to which world, and whether it is kept for it."""

    at: float
    who: str
    kept: bool


def machine_slots_file(state_dir: Path) -> Path:
    """Where a class server keeps its machine's start slots, shared with the world workers it
    starts here (they are told this path)."""
    return state_dir / "start-slots"


def stretch(skipped: float) -> float:
    """How many times as far apart the turns come when the worlds skipped ``skipped`` of their
    timer calls: 1 up to ``SKIPPED_OK``, rising evenly to ``MAX_STRETCH`` at ``SKIPPED_MOST``."""
    if not skipped > SKIPPED_OK:  # NaN too: a reading that says nothing slows nothing
        return 1.0
    return 1.0 + (MAX_STRETCH - 1.0) * min(1.0, (skipped - SKIPPED_OK) / (SKIPPED_MOST - SKIPPED_OK))


def loop_hold_s() -> float:
    """How long a start holds its slot on a pacer the worlds' loop thread builds (a lab's, a class's):
    ``HOLD_S`` while that thread runs in the real-time class, else ``FAIR_LOOP_HOLD_S``."""
    return HOLD_S if scheduling_of(0) == "realtime" else FAIR_LOOP_HOLD_S


def default_slots() -> int:
    """One start at a time per core the server does not need (at least one; the cores it may use,
    as its affinity and CPU quota allow)."""
    return max(1, usable_cores() - 1)


class StartPacer:
    """At most ``slots`` starts admitted within any ``hold_s`` (None: as the building thread's class
    allows, ``loop_hold_s``), longer while the worlds skip their timers' calls (``skipped`` says
    what share of them they skipped lately); ``clock`` is injected for tests."""

    def __init__(
        self,
        slots: int,
        hold_s: float | None = None,
        clock: Callable[[], float] = time.monotonic,
        skipped: Callable[[], float] | None = None,
    ) -> None:
        hold_s = loop_hold_s() if hold_s is None else hold_s
        if slots < 1 or hold_s <= 0:
            raise ValueError(f"a start pacer needs slots >= 1 and hold_s > 0, got {slots} and {hold_s}")
        self.slots, self.hold_s, self._clock = slots, hold_s, clock
        self.skipped = skipped
        self.stretched = 0  # starts after which the turns moved back, as the worlds skipped calls
        self._held: list[float] = []  # when each held slot frees, oldest first
        self._last_turn = -math.inf  # the latest turn given to a deferred start
        # The turns given, by ticket: when, to whom (a world's name), and whether it is kept for
        # its start (a start that keeps no ticket gets one too, never told it, counted to its world).
        self._turns: dict[str, Given] = {}
        self.admitted = 0
        self.deferred = 0
        self._lock = threading.Lock()  # the API's joins and the launcher's starts may ask at once

    def admit(self, ticket: str | None = None, who: str = "") -> Turn | None:
        """None if this start may go ahead now (it holds a slot), else its ``Turn``: when the first
        slot frees, and after every turn given before it (one slot's share of ``hold_s`` apart), so
        each waiting start asks again about once. ``ticket``: ``NEW_TURN`` for a start that will
        come back with the ticket it is given, which keeps its turn; a ticket given before, to go
        at its turn or later (one unknown or given up: a new start's); None for a start that
        keeps no ticket, as before there were any (see ``_admit``). ``who``: the world asking
        (empty for a lab's own user), whose waiting turns are at most ``MAX_WAITING``."""
        with self._lock:
            return self._admit(self._clock(), ticket, who, self._own_skipped())

    def _own_skipped(self) -> float:
        """The share of calls this process's worlds skipped lately, 0 for no reading (or no share)."""
        share = self.skipped() if self.skipped is not None else 0.0
        return share if 0.0 <= share <= 1.0 else 0.0

    def _admit(self, now: float, ticket: str | None, who: str, skipped: float = 0.0) -> Turn | None:
        # A slot that frees within a quarter of ``hold_s`` counts as free. The start ahead may have
        # been admitted a little late, so its slot frees a little after the next start's turn: that
        # start goes at its turn, not to the back of the line (60 paced starts took 104 s so).
        early = self.hold_s * GRACE
        self._held = [t for t in self._held if t > now + early]
        self._turns = {k: g for k, g in self._turns.items() if g.at + KEPT_S > now}
        given = self._turns.get(ticket) if ticket is not None else None
        if ticket is not None and given is not None and given.kept and given.who == who:
            if given.at - now > early:  # back before its turn: it keeps it
                self.deferred += 1
                return Turn(given.at - now, ticket)
            del self._turns[ticket]
            self._go(now, skipped)
            return None
        # A kept turn's slot is set aside from a quarter hold before it until a hold after it (its
        # start a little late). A start that keeps no ticket is never given a turn kept for it: it
        # comes back as a new start, and its own kept turn would then always be in its way.
        due = sum(1 for g in self._turns.values() if g.kept and now - self.hold_s < g.at < now + early)
        if len(self._held) + due < self.slots:
            self._go(now, skipped)
            return None
        self.deferred += 1
        first_free = self._held[0] if self._held else now
        turn_at = max(now, first_free, self._last_turn + self.hold_s / self.slots)
        waiting = sum(1 for g in self._turns.values() if g.who == who)
        if waiting >= MAX_WAITING or len(self._turns) >= MAX_TURNS:
            return Turn(turn_at - now)  # the end of the line, which it does not move
        self._last_turn = turn_at
        # ``NEW_TURN``, or a ticket unknown here (forged, or given up): a start that keeps one.
        kept = ticket is not None
        name = secrets.token_urlsafe(12)
        self._turns[name] = Given(turn_at, who, kept)
        return Turn(turn_at - now, name if kept else None)

    def _go(self, now: float, skipped: float) -> None:
        times = stretch(skipped)
        self._held.append(now + self.hold_s * times)
        self._held.sort()
        self.admitted += 1
        if times > 1.0:  # every turn given moves back, in its order: the next start comes later
            later = (times - 1.0) * self.hold_s / self.slots
            self._turns = {k: dataclasses.replace(g, at=g.at + later) for k, g in self._turns.items()}
            if math.isfinite(self._last_turn):
                self._last_turn += later
            self.stretched += 1


class MachineStartPacer(StartPacer):
    """A ``StartPacer`` whose slots every process on this machine that names the same ``path``
    shares: the held slots, the latest turn and the turns kept live in that file (a ticket one
    process gave goes in any of them), read and written under an
    exclusive ``flock``. The clock must be the machine's (``time.monotonic``: the same in every
    process of one boot), as a time in the file is read by the others.

    It never blocks its caller (the server's event loop): a lock another process holds at that
    instant defers the start by ``BUSY_WAIT_S``, and a file it cannot open or read paces this
    process alone, as a ``StartPacer`` does (logged once)."""

    def __init__(
        self,
        path: Path,
        slots: int,
        hold_s: float | None = None,
        clock: Callable[[], float] = time.monotonic,
        skipped: Callable[[], float] | None = None,
    ) -> None:
        super().__init__(slots, hold_s, clock, skipped)
        self.path = path
        self._name = f"{os.getpid()}:{secrets.token_hex(4)}"  # what it says it skipped is kept under this
        self._alone = False  # the file failed once: this process paces itself from then on

    def admit(self, ticket: str | None = None, who: str = "") -> Turn | None:
        with self._lock:
            now, skipped = self._clock(), self._own_skipped()
            if self._alone:
                return self._admit(now, ticket, who, skipped)
            try:
                return self._admit_shared(now, ticket, who, skipped)
            except OSError as exc:
                self._alone = True
                log.warning(
                    "node starts paced by this process alone: the slots file %s failed: %s", self.path, exc
                )
                return self._admit(now, ticket, who, skipped)

    def _admit_shared(self, now: float, ticket: str | None, who: str, skipped: float) -> Turn | None:
        self.path.parent.mkdir(parents=True, exist_ok=True)
        fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o600)
        try:
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                self.deferred += 1
                return Turn(BUSY_WAIT_S, ticket)  # a ticket it came with is still good
            self._held, self._last_turn, self._turns, said = _read_slots(fd)
            # What this process's worlds skipped, beside what the others sharing the slots said lately.
            said = {k: v for k, v in said.items() if now - SKIPPED_FRESH_S < v[0] <= now}
            said[self._name] = (now, skipped)
            turn = self._admit(now, ticket, who, max(share for _at, share in said.values()))
            last = None if math.isinf(self._last_turn) else self._last_turn
            turns = {k: [g.at, g.who, g.kept] for k, g in self._turns.items()}
            shared = {k: list(v) for k, v in said.items()}
            text = json.dumps(
                {"boot": BOOT_ID, "held": self._held, "last_turn": last, "turns": turns, "skipped": shared}
            )
            os.lseek(fd, 0, os.SEEK_SET)
            os.ftruncate(fd, 0)
            os.write(fd, text.encode())
            return turn
        finally:
            os.close(fd)  # and with it the lock


def _boot_id() -> str:
    """This boot's id (Linux): times on the monotonic clock compare only within one boot."""
    try:
        return Path("/proc/sys/kernel/random/boot_id").read_text().strip()
    except OSError:
        return ""


BOOT_ID = _boot_id()


Said = dict[str, tuple[float, float]]  # by pacer (its process id first): when it said so, the share


def _read_slots(fd: int) -> tuple[list[float], float, dict[str, Given], Said]:
    """The held slots, the latest turn, the turns given and what each process skipped that a slots
    file holds; none (a fresh state) where it is empty, not what this module writes, or written in
    another boot."""
    try:
        data = json.loads(os.pread(fd, 65536, 0) or b"{}")
        held = sorted(float(t) for t in data["held"])
        last = -math.inf if data["last_turn"] is None else float(data["last_turn"])
        turns = {str(k): _given(v) for k, v in data.get("turns", {}).items()}
        said = {str(k): _said(v) for k, v in data.get("skipped", {}).items()}
        times = [*held, max(last, 0.0), *(g.at for g in turns.values()), *(at for at, _ in said.values())]
        if (
            data["boot"] != BOOT_ID
            or not all(math.isfinite(t) for t in times)
            or len(turns) > MAX_TURNS
            or len(said) > MAX_TURNS
        ):
            return [], -math.inf, {}, {}
        return held, last, turns, said
    except (ValueError, TypeError, KeyError, AttributeError):
        return [], -math.inf, {}, {}


def _said(entry: object) -> tuple[float, float]:
    """What a process skipped as the file holds it, ``[at, share]`` with the share in [0, 1];
    ValueError for anything else."""
    if not isinstance(entry, list) or len(entry) != 2:
        raise ValueError(f"not a share skipped: {entry!r}")
    at, share = float(entry[0]), float(entry[1])
    if not 0.0 <= share <= 1.0:
        raise ValueError(f"not a share skipped: {entry!r}")
    return at, share


def _given(entry: object) -> Given:
    """A turn as the file holds it, ``[at, who, kept]``; ValueError for anything else."""
    if not isinstance(entry, list) or len(entry) != 3:
        raise ValueError(f"not a turn: {entry!r}")
    at, who, kept = entry
    if not isinstance(who, str) or not isinstance(kept, bool):
        raise ValueError(f"not a turn: {entry!r}")
    return Given(float(at), who, kept)
