"""One asyncio task that runs the executors of many buses (a class server's worlds), a fair turn each.

Each world keeps its own bus, executor and timers (their phases stay spread, so no instant
carries every world's work); what the group shares is the waiting. A task per world would wake
once for every world's every deadline; on a class server of 30 worlds those wake-ups took about
half as much time as the worlds' own callbacks (py-spy). The group wakes once for whatever is
due, gives each world with work a turn, then sleeps until the soonest deadline of any.

The worlds share one loop thread, so the group shares it out: every world is charged the time its
callbacks take (its *usage*, decaying by half every ``half_life_s``, kept by the world's name so
that a reset does not clear it), each round gives the worlds their turns from the least used to
the most, and a turn ends once it has taken ``turn_s``. A world with a backlog (a student's
extra launches, a flood of its own messages) goes on in the next round, after the others' due
ticks, instead of holding them up: a quiet world's tick waits at most about one turn.
"""

from __future__ import annotations

import contextlib
import logging
import math
import time
from collections.abc import Callable, Hashable
from typing import TYPE_CHECKING

from node_runtime.bus.executor import Executor, _Sleep

if TYPE_CHECKING:
    import asyncio
# asyncio is imported where the loop is used, as in executor.py: a node process never loads it.

log = logging.getLogger("bus.executor")
TURN_S = 0.002  # a world's share of a round; a 100 Hz tick elsewhere waits at most about this
HALF_LIFE_S = 1.0  # a world's usage halves in this long (on the cost clock)
DECAY_EVERY_S = 0.05  # usage decays in steps this long, not on every round
FORGET_BELOW_S = 1e-6  # the usage of a world no longer in the group is dropped once this small


class ExecutorGroup:
    """Runs many executors on one task; ``cost_clock`` measures what their callbacks take
    (``time.perf_counter`` in the app; a test hands in one its callbacks move)."""

    def __init__(
        self,
        cost_clock: Callable[[], float] = time.perf_counter,
        turn_s: float = TURN_S,
        half_life_s: float = HALF_LIFE_S,
    ) -> None:
        if not (turn_s > 0 and half_life_s > 0):
            raise ValueError(f"turn_s and half_life_s must be positive, got {turn_s} and {half_life_s}")
        self.cost_clock, self.turn_s, self.half_life_s = cost_clock, turn_s, half_life_s
        self._wakers: dict[Executor, Callable[[], None]] = {}
        self._members: list[Executor] = []
        self._account: dict[Executor, Hashable] = {}  # whose usage a member's time goes to
        self._usage: dict[Hashable, float] = {}  # decayed seconds of callbacks, by account
        self._decayed_at = cost_clock()
        self._turn_end = 0.0  # on the cost clock: when the running turn is over
        self._over = self._turn_over  # bound once: asked between every two callbacks of a turn
        self._woken: set[Executor] = set()  # had news (a message, a timer, a thread's hand-in)
        self._sleep = _Sleep()
        self._task: asyncio.Task[None] | None = None
        self._stopping = False

    def __len__(self) -> int:
        return len(self._members)

    def add(self, executor: Executor, charge_s: float = 0.0) -> None:
        """Run ``executor``'s bus from now on (on the running loop; starts the group's task). Its
        time is charged to its bus's label (a world's name) if it has one, starting with
        ``charge_s`` (what its start took of the loop)."""
        if executor in self._wakers:
            return
        import asyncio

        loop = asyncio.get_running_loop()

        def wake() -> None:
            self._woken.add(executor)
            self._sleep.wake()

        def wake_from_thread() -> None:
            with contextlib.suppress(RuntimeError):  # the loop closed while another thread had news
                loop.call_soon_threadsafe(wake)

        self._wakers[executor] = wake
        self._members.append(executor)
        key = self._account[executor] = executor.bus.label or executor
        self._usage[key] = self._usage.get(key, 0.0) + max(0.0, charge_s)
        executor.bus.add_waker(wake)
        executor.bus.threadsafe_waker = wake_from_thread
        wake()
        if self._task is None or self._task.done():
            self._stopping = False
            self._task = loop.create_task(self._spin(), name="executors")

    def remove(self, executor: Executor) -> None:
        """Stop running ``executor``'s bus; its callbacks never run again after this returns. Its
        world's usage stays (and decays) so a world started again under the same name keeps it."""
        wake = self._wakers.pop(executor, None)
        if wake is None:
            return
        self._members.remove(executor)
        self._woken.discard(executor)
        self._account.pop(executor, None)
        executor.bus.remove_waker(wake)
        executor.bus.threadsafe_waker = None

    def usage_s(self, executor: Executor) -> float:
        """Seconds of callbacks charged to ``executor``'s world, decayed to the latest round."""
        return self._usage.get(self._account.get(executor, executor), 0.0)

    async def close(self) -> None:
        """Stop the group's task (the members stay added: ``remove`` them first)."""
        self._stopping = True
        self._sleep.wake()
        if self._task is not None:
            await self._task
            self._task = None

    def wake(self) -> None:
        """Have the group look at its members now (on the loop's thread): after a ManualClock moved."""
        self._sleep.wake()

    # -- charging ----------------------------------------------------------
    def _decay(self, now: float) -> None:
        elapsed = now - self._decayed_at
        if elapsed < DECAY_EVERY_S * self.half_life_s:
            return
        self._decayed_at = now
        factor = 0.5 ** (elapsed / self.half_life_s)
        members = set(self._account.values())
        for key, used in list(self._usage.items()):
            used *= factor
            if used < FORGET_BELOW_S and key not in members:
                del self._usage[key]
            else:
                self._usage[key] = used

    def _turn_over(self) -> bool:
        return self.cost_clock() >= self._turn_end

    def _turn(self, executor: Executor) -> None:
        """One turn of ``executor``: at most ``turn_s`` of its callbacks (at least one), charged."""
        start = self.cost_clock()
        self._turn_end = start + self.turn_s
        try:
            executor.spin_some(self._over)
        finally:
            key = self._account.get(executor, executor)
            self._usage[key] = self._usage.get(key, 0.0) + max(0.0, self.cost_clock() - start)

    # -- the rounds --------------------------------------------------------
    def _round(self) -> tuple[bool, float]:
        """A turn for every member with work, the least used first; returns (some member still
        has work, seconds to the soonest deadline)."""
        self._decay(self.cost_clock())
        woken, due = self._woken, []
        busy, soonest = False, math.inf
        for executor in self._members:
            bus = executor.bus
            deadline, now = executor.next_deadline_s(), bus.clock.now()
            if executor in woken or bus._ready or bus._calls or deadline <= now:
                due.append(executor)
            else:
                soonest = min(soonest, deadline - now)
        if len(due) > 1:
            usage, account = self._usage, self._account
            due.sort(key=lambda e: usage.get(account.get(e, e), 0.0))
        for executor in due:
            if executor not in self._wakers:
                continue  # removed by an earlier member's callback in this round
            try:
                self._turn(executor)
            except Exception:  # one world's broken executor must not stop the others
                log.exception("a world's executor failed; it stops, the others go on")
                self.remove(executor)
                continue
            woken.discard(executor)  # what it published in its turn it has delivered, or left queued
            bus = executor.bus
            if bus._ready or bus._calls:
                busy = True
            else:  # a timer its turn left due makes this 0 or less: the next round comes at once
                soonest = min(soonest, executor.next_deadline_s() - bus.clock.now())
        return busy or bool(woken), soonest

    async def _spin(self) -> None:
        while not self._stopping:
            busy, delay = self._round()
            await self._sleep(0.0 if busy else delay)
