"""How many node processes may start at once on this server. A start is admitted into one of a
few slots, each held for about as long as a node process takes to import its libraries and join;
a start that finds every slot held is told the time of its turn, after the starts told to come
back before it. Two kinds of start ask: ``GET /api/zenoh/join?start=true`` (a node process about
to start, as ``ros2lab run`` asks; api/lab_routes.py answers a deferred one 429 with
``Retry-After``, and ``ros2lab run`` waits that long and asks again), and, where the server
serves others, a student's node the page's Run or Launch starts (server/launch/launcher.py
keeps it waiting, then starts it at its turn). A join without ``start`` (``ros2lab env``, a tool
reading the router) is never paced. A server process has one pacer: its cores are shared.

Why: a node's start is a burst of CPU (the interpreter, rclpy, the messages, the Zenoh session).
Sixty of them at once on a 2-core class server (a class told "run it now") share the cores with
the worlds' loops, and the scheduler gives every runnable process its share: the worlds fell
behind and a page's WebSocket handshake waited over 10 s. Paced, at most ``slots`` starts share
the cores with the server at any moment, and a burst is all joined at about ``slots / hold_s``
starts a second.
"""

from __future__ import annotations

import math
import os
import threading
import time
from collections.abc import Callable

HOLD_S = 1.0  # a handout node's start on an idle 2-core machine: about 0.5 s of CPU, 0.8 s to listed


def default_slots() -> int:
    """One start at a time per core the server does not need (at least one)."""
    return max(1, (os.cpu_count() or 2) - 1)


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
        self._held = [t for t in self._held if t > now]
        if len(self._held) < self.slots:
            self._held.append(now + self.hold_s)
            self.admitted += 1
            return None
        self.deferred += 1
        self._last_turn = max(self._held[0], self._last_turn + self.hold_s / self.slots)
        return self._last_turn - now
