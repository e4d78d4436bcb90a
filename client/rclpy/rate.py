"""``node.create_rate(hz)``: a loop at a steady frequency (the handout's "Method 1")."""

from __future__ import annotations

import threading
import time

from server.bus.blocking import BlockingExecutor

from ._context import Context


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
        _bus, executor = self._context.require()
        others_spin = bool(executor.spinning_threads - {threading.get_ident()})
        if others_spin:
            time.sleep(max(0.0, deadline - time.monotonic()))
            return
        while True:
            left = deadline - time.monotonic()
            if left <= 0 or not self._context.ok():
                return
            _spin_for(executor, left)

    def destroy(self) -> None:
        self._destroyed = True


def _spin_for(executor: BlockingExecutor, seconds: float) -> None:
    executor.spin_once(seconds)
