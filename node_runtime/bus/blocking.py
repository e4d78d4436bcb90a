"""An executor for a node's own process: it blocks its thread while nothing is due, as rclpy's do.

It waits on a condition until the next timer's deadline or a wake-up (a message from Zenoh's
threads, a publish from another thread), so a node process idles at no CPU. Faults are not
caught: an exception in a callback ends ``spin`` and, unless the student's code catches it, the
process, with its traceback, as in ROS 2.
"""

from __future__ import annotations

import math
import threading
from collections.abc import Callable

from node_runtime.bus.executor import Executor
from node_runtime.bus.graph import Bus

MAX_WAIT_S = 1.0  # a wait is re-checked at least this often (a clock that jumps, a stop request)


class BlockingExecutor(Executor):
    propagate_faults = True

    def __init__(self, bus: Bus) -> None:
        super().__init__(bus)
        # The condition's own lock is taken directly (a C call, where ``with self._cv`` runs
        # Python's), and a wake notifies only while a thread sleeps on it: a wake comes with each
        # message from Zenoh's threads and each callback's end, mostly while no thread sleeps.
        self._cv_lock = threading.Lock()
        self._cv = threading.Condition(self._cv_lock)
        self._sleeping = 0
        self._woken = False
        self.spinning_threads: set[int] = set()
        bus.threadsafe_waker = self.wake
        bus.add_waker(self.wake)

    def wake(self) -> None:
        with self._cv_lock:
            self._woken = True
            if self._sleeping:
                self._cv.notify_all()

    def _has_news(self) -> bool:
        """Whether a wake-up came that the coming wait must not sleep through (under ``_cv``)."""
        return self._woken

    def _wait(self, until_s: float) -> None:
        """Block until ``until_s`` on the bus clock, the next timer, or a wake-up, whichever is first."""
        delay = min(until_s, self.next_deadline_s()) - self.bus.clock.now()
        with self._cv_lock:
            if not self._has_news() and delay > 0:
                self._sleeping += 1
                try:
                    self._cv.wait(min(delay, MAX_WAIT_S) if math.isfinite(delay) else MAX_WAIT_S)
                finally:
                    self._sleeping -= 1
            self._woken = False

    def spin_once(self, timeout_s: float | None = None) -> int:
        """Run what is ready; if nothing was, wait (at most ``timeout_s``) and run what came."""
        ident = threading.get_ident()
        self.spinning_threads.add(ident)
        try:
            ran = self.spin_some()
            if ran or timeout_s == 0:
                return ran
            deadline = math.inf if timeout_s is None or timeout_s < 0 else self.bus.clock.now() + timeout_s
            self._wait(deadline)
            return self.spin_some()
        finally:
            self.spinning_threads.discard(ident)

    def run_until(self, done: Callable[[], bool], timeout_s: float | None = None) -> bool:
        """Spin until ``done()`` (True) or ``timeout_s`` passes (False); forever with no timeout."""
        ident = threading.get_ident()
        self.spinning_threads.add(ident)
        try:
            end = math.inf if timeout_s is None or timeout_s < 0 else self.bus.clock.now() + timeout_s
            while not done():
                if self._stopping:
                    return False
                self.spin_some()
                if done():
                    return True
                now = self.bus.clock.now()
                if now >= end:
                    return False
                self._wait(end)
            return True
        finally:
            self.spinning_threads.discard(ident)

    def spin_forever(self) -> None:
        self._stopping = False
        self.run_until(lambda: self._stopping)

    def stop(self) -> None:
        self._stopping = True
        self.wake()
