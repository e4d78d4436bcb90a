"""The executor: runs subscription and timer callbacks, on the asyncio loop or stepped by hand.

Callbacks never run inside ``publish``: it only queues. An exception in a callback is logged
with the node's name and marks that node crashed; every other node keeps running.
"""

from __future__ import annotations

import contextlib
import heapq
import logging
import math
import traceback
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from node_runtime.bus.endpoints import Subscription
from node_runtime.bus.faults import is_node_fault
from node_runtime.bus.graph import Bus
from node_runtime.bus.node import Node
from node_runtime.bus.services import PendingCall

if TYPE_CHECKING:
    import asyncio

# asyncio (with ssl, about 10 MiB) is imported where the loop is used: a node process's executor
# blocks a thread instead and never loads it.
log = logging.getLogger("bus.executor")
MAX_CALLBACKS_PER_PASS = 10_000  # bounds a node that keeps re-triggering itself
TurnOver = Callable[[], bool]  # asked between callbacks: has this world's turn run out?


class _Sleep:
    """An event-loop wait that ends when ``wake()`` is called or ``delay`` seconds pass."""

    def __init__(self) -> None:
        self._waiter: asyncio.Future[None] | None = None

    def wake(self) -> None:
        if self._waiter is not None and not self._waiter.done():
            self._waiter.set_result(None)

    async def __call__(self, delay: float) -> None:
        import asyncio

        if delay <= 0:
            await asyncio.sleep(0)  # let the API and WebSockets in between bursts
            return
        loop = asyncio.get_running_loop()
        self._waiter = loop.create_future()
        handle = loop.call_later(delay, self.wake) if math.isfinite(delay) else None
        try:
            await self._waiter
        finally:
            self._waiter = None
            if handle is not None:
                handle.cancel()


class Executor:
    """Drains a bus: ``spin_some``/``spin_until`` for tests, ``await spin()`` for the app."""

    # In the app a fault stays inside its node; a node process lets it end the process, as rclpy does.
    propagate_faults = False

    def __init__(self, bus: Bus) -> None:
        self.bus = bus
        self._sleep = _Sleep()
        self._wake = self._sleep.wake
        self._stopping = False
        self.callbacks_run = 0

    # -- one callback ------------------------------------------------------
    def _run(self, node: Node, fn: Callable[..., Any], *args: Any) -> None:
        try:
            fn(*args)
        except BaseException as exc:  # the lab's point: a fault stays inside its node
            if self.propagate_faults or not is_node_fault(exc):
                raise
            log.error(
                "%s crashed in %s:\n%s",
                self.bus.tagged(f"node {node.fully_qualified_name}"),
                getattr(fn, "__qualname__", fn),
                traceback.format_exc(),
            )
            with contextlib.suppress(Exception):
                node.get_logger().fatal(f"crashed: {type(exc).__name__}: {exc}")
            node.mark_crashed(exc)
        self.callbacks_run += 1

    def _run_subscription(self, sub: Subscription) -> bool:
        if sub.destroyed or sub.node._state != "active" or not sub.queue:  # not sub.active, inline
            return False
        self._run(sub.node, sub.callback, sub.queue.popleft())
        return True

    def _run_due_timers(self, now_s: float, turn_over: TurnOver | None = None) -> int:
        heap, seq = self.bus._timers, self.bus._seq
        ran = 0
        while heap and heap[0][0] <= now_s:
            if ran and turn_over is not None and turn_over():
                break  # the rest stay due: the group's next round runs them
            deadline, _, timer = heapq.heappop(heap)
            if timer.cancelled or timer.node._state != "active" or deadline != timer.next_deadline_s:
                continue  # stale entry (cancelled, reset, or a crashed node)
            timer.advance_past(now_s)
            # Bus.schedule without its wake-up: this executor is already running.
            heapq.heappush(heap, (timer.next_deadline_s, next(seq), timer))
            timer.call_count += 1
            self._run(timer.node, timer.callback)
            # Deliver what it published before the next timer due at the same instant runs, so
            # a chain of nodes ticking together sees fresh data, not last period's.
            ran += 1 + self._drain(turn_over)
        return ran

    def _run_call(self, call: PendingCall) -> bool:
        server = call.server
        if not server.active:
            return False  # the server went away: the client keeps waiting, as in ROS 2
        self._run(server.node, server.answer, call)
        return True

    def _drain(self, turn_over: TurnOver | None = None) -> int:
        ready, calls = self.bus._ready, self.bus._calls
        ran = 0
        while (ready or calls) and ran < MAX_CALLBACKS_PER_PASS:
            if ran and turn_over is not None and turn_over():
                break  # the rest wait in their queues for the world's next turn
            if ready and self._run_subscription(ready.popleft()):
                ran += 1
            if calls and self._run_call(calls.popleft()):
                ran += 1
        return ran

    # -- stepping ----------------------------------------------------------
    def spin_some(self, turn_over: TurnOver | None = None) -> int:
        """Take what other threads handed in, run every queued message, then every due timer;
        returns how many callbacks ran. With ``turn_over`` (an ExecutorGroup's turn), stop once it
        says so: what is left stays queued or due. A turn runs at least one queued message and one
        due timer, so a world whose queue never empties still ticks."""
        lock = self.bus.lock
        if lock is None:
            return self._pass(turn_over)
        with lock:
            return self._pass(turn_over)

    def _pass(self, turn_over: TurnOver | None) -> int:
        for poll in self.bus.pollers:
            poll()
        ran = self._drain(turn_over)
        return ran + self._run_due_timers(self.bus.clock.now(), turn_over)

    def next_deadline_s(self) -> float:
        heap = self.bus._timers
        while heap and (
            heap[0][2].cancelled
            or heap[0][2].node._state != "active"
            or heap[0][0] != heap[0][2].next_deadline_s
        ):
            heapq.heappop(heap)
        return heap[0][0] if heap else math.inf

    def spin_until(self, t_end_s: float) -> int:
        """With a ManualClock: move time to ``t_end_s``, firing each timer at its exact deadline."""
        clock = self.bus.clock
        set_time = getattr(clock, "set", None)
        if set_time is None:
            raise TypeError("spin_until needs a clock that can be set (ManualClock)")
        ran = self.spin_some()
        while True:
            deadline = self.next_deadline_s()
            if deadline > t_end_s:
                break
            set_time(max(deadline, clock.now()))
            ran += self.spin_some()
        set_time(max(t_end_s, clock.now()))
        return ran + self.spin_some()

    def spin_for(self, duration_s: float) -> int:
        return self.spin_until(self.bus.clock.now() + duration_s)

    # -- the asyncio loop ----------------------------------------------------
    async def spin(self) -> None:
        """Run callbacks as they come due until ``stop()``; sleeps between them, never busy-waits."""
        import asyncio

        loop = asyncio.get_running_loop()
        self._stopping = False
        self.bus.add_waker(self._wake)

        def wake_from_thread() -> None:
            with contextlib.suppress(RuntimeError):  # the loop closed while another thread had news
                loop.call_soon_threadsafe(self._wake)

        self.bus.threadsafe_waker = wake_from_thread
        try:
            while not self._stopping:
                self.spin_some()
                busy = bool(self.bus._ready or self.bus._calls)
                await self._sleep(0.0 if busy else self.next_deadline_s() - self.bus.clock.now())
        finally:
            self.bus.remove_waker(self._wake)
            self.bus.threadsafe_waker = None

    def stop(self) -> None:
        self._stopping = True
        self._wake()
