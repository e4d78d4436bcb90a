"""The join queue: while the class's verdict is ``full`` (capacity.py), a new student's join waits
here instead of starting a world that would slow every other one.

A waiting join holds a ticket (a random secret; the join page polls with it) and its world's name
(no second join takes it meanwhile). It is admitted oldest first, when the verdict is no longer
full or the instructor lets joins through. A join past ``size`` waiting is refused at once, and
one that waited ``wait_s`` in all, or was not polled for ``abandon_s`` (its page closed), is
dropped: 503 with ``Retry-After``, naming why. Time is the class's clock, so tests step it.
"""

from __future__ import annotations

import secrets
from dataclasses import dataclass
from typing import Any

from node_runtime.bus import Clock
from server.classroom.errors import AtCapacityError, JoinLapsedError, UnknownTicketError
from server.host.settings import JoinQueueSettings


@dataclass
class Waiting:
    """One join waiting: its ticket, who and from where, since when, and when it was last polled."""

    ticket: str
    student: str
    world: str
    address: str
    since_s: float
    polled_s: float


class JoinWaits(Exception):
    """A join that waits in the queue: the route answers 202 with its ticket."""

    def __init__(self, waiting: Waiting, ahead: int) -> None:
        super().__init__(f"{waiting.student} waits to join, {ahead} ahead")
        self.waiting = waiting
        self.ahead = ahead


class JoinQueue:
    """Joins waiting for room, oldest first, bounded in count and time."""

    def __init__(self, settings: JoinQueueSettings, clock: Clock) -> None:
        self.settings = settings
        self.clock = clock
        self._waiting: list[Waiting] = []
        self._gone: dict[str, str] = {}  # ticket → why it left the queue unadmitted (the last few)
        self.let_through = 0  # joins the instructor let past a full verdict, not yet used
        self.admitted = 0
        self.refused = 0

    def __len__(self) -> int:
        return len(self._waiting)

    def holds(self, world: str) -> bool:
        return any(w.world == world for w in self._waiting)

    def add(self, student: str, world: str, address: str) -> Waiting:
        """A join that must wait: AtCapacityError (saying when to try again) when the queue is already
        full."""
        self.expire()
        if len(self._waiting) >= self.settings.size:
            self.refused += 1
            raise AtCapacityError(
                f"the class server is at its capacity and {len(self._waiting)} joins already wait "
                f"(at most {self.settings.size}): try again in {self.settings.retry_after_s:g} s",
                self.settings.retry_after_s,
            )
        now = self.clock.now()
        waiting = Waiting(secrets.token_urlsafe(18), student, world, address, now, now)
        self._waiting.append(waiting)
        return waiting

    def find(self, ticket: str) -> tuple[Waiting, int]:
        """The join holding ``ticket`` and how many wait ahead of it (this poll keeps it alive);
        UnknownTicketError for a ticket never given, JoinLapsedError for one dropped, naming why."""
        self.expire()
        for ahead, waiting in enumerate(self._waiting):
            if secrets.compare_digest(waiting.ticket, ticket):
                waiting.polled_s = self.clock.now()
                return waiting, ahead
        why = self._gone.pop(ticket, None)
        if why is not None:
            raise JoinLapsedError(why, self.settings.retry_after_s)
        raise UnknownTicketError("no join waits with this ticket: join again")

    def remove(self, waiting: Waiting) -> None:
        if waiting in self._waiting:
            self._waiting.remove(waiting)

    def admit(self, waiting: Waiting) -> None:
        """``waiting`` leaves the queue to start its world now."""
        self.remove(waiting)
        self.admitted += 1

    def let_in(self, count: int) -> None:
        """The instructor lets ``count`` more joins past a full verdict (oldest first)."""
        self.let_through += count

    def use_let_through(self) -> bool:
        if self.let_through <= 0:
            return False
        self.let_through -= 1
        return True

    def expire(self) -> None:
        """Drop the joins that waited too long in all, or whose page stopped polling."""
        now = self.clock.now()
        for waiting in list(self._waiting):
            if now - waiting.since_s >= self.settings.wait_s:
                why = (
                    f"the class server stayed at its capacity for {self.settings.wait_s:g} s while your "
                    f"join waited: try again in {self.settings.retry_after_s:g} s, or ask the instructor"
                )
            elif now - waiting.polled_s >= self.settings.abandon_s:
                why = f"your join was not polled for {self.settings.abandon_s:g} s and left the queue"
            else:
                continue
            self._waiting.remove(waiting)
            self.refused += 1
            self._gone[waiting.ticket] = why
            while len(self._gone) > 4 * self.settings.size:  # the oldest reasons go first
                del self._gone[next(iter(self._gone))]

    def describe(self) -> dict[str, Any]:
        now = self.clock.now()
        return {
            "waiting": [
                {"student": w.student, "world": w.world, "waited_s": round(now - w.since_s, 1)}
                for w in self._waiting
            ],
            "size": self.settings.size,
            "wait_s": self.settings.wait_s,
            "let_through": self.let_through,
            "admitted": self.admitted,
            "refused": self.refused,
        }
