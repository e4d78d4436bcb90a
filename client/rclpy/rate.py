"""``node.create_rate(hz)``: a loop at a steady frequency (the handout's "Method 1")."""

from __future__ import annotations

import time
import weakref
from typing import Any, cast

from rclpy._context import Context
from rclpy._wait_set import WaitSet
from rclpy.executors import SingleThreadedExecutor


class Rate:
    """``sleep()`` waits until the next multiple of the period since the rate was made, so the loop
    keeps its frequency whatever its body takes. While it waits the process's callbacks run, as they
    would in ROS 2 with ``spin`` in another thread; if another thread spins, it only waits."""

    def __init__(self, frequency: float, context: Context) -> None:
        if not frequency > 0:
            raise ValueError(f"a rate must be positive, got {frequency!r} Hz")
        self.period_s = 1.0 / frequency
        self._context = context
        self._start = time.monotonic()
        self._ticks = 0
        self._destroyed = False

    def _next_deadline(self) -> float:
        now = time.monotonic()
        self._ticks = max(self._ticks + 1, int((now - self._start) / self.period_s) + 1)
        return self._start + self._ticks * self.period_s

    def sleep(self) -> None:
        if self._destroyed:
            raise RuntimeError("this rate was destroyed")
        deadline = self._next_deadline()
        _bus, wait_set = self._context.require()
        if cast(WaitSet, wait_set).spun_elsewhere():
            time.sleep(max(0.0, deadline - time.monotonic()))
            return
        runner = _runner(self._context, cast(WaitSet, wait_set))
        while True:
            left = deadline - time.monotonic()
            if left <= 0 or not self._context.ok():
                return
            runner.spin_once(left)

    def destroy(self) -> None:
        self._destroyed = True

    @property
    def destroyed(self) -> bool:
        return self._destroyed


class _EveryNode(SingleThreadedExecutor):
    """Runs the callbacks of every node of the process (no one spins them while a rate sleeps)."""

    def get_nodes(self) -> list[Any]:
        bus = self._context.bus
        return [] if bus is None else list(bus.nodes)


_runners: weakref.WeakKeyDictionary[WaitSet, _EveryNode] = weakref.WeakKeyDictionary()


def _runner(context: Context, wait_set: WaitSet) -> _EveryNode:
    runner = _runners.get(wait_set)
    if runner is None:
        runner = _runners[wait_set] = _EveryNode(context=context)
    return runner
