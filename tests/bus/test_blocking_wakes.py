"""A node process's waits end on the news they wait for, however the news and the wait interleave.

The blocking executor notifies its condition only while a thread sleeps on it, and a bus future
makes its event only when a thread first waits on it: both spare every tick of a node some calls,
and both would lose a wake-up if the check for news and the sleep could be split. Each test races
the two sides a thousand times from two threads, each side starting after a different amount of
work; a lost wake-up shows as a wait that ran to its timeout (the executor sleeps a second at a
time at most, the future's waits are given 10 s), which the tests record and fail on. A check and
sleep split apart in either (a loop of a hundred steps between them, tried) fails them.
"""

from __future__ import annotations

import functools
import sys
import threading
from collections.abc import Callable, Iterator

import pytest

from node_runtime.bus import Bus
from node_runtime.bus.blocking import BlockingExecutor
from node_runtime.bus.clock import SystemClock
from node_runtime.bus.services import Future

ROUNDS = 1000
LONG_S = 10.0  # a wait that runs this long lost its wake-up


class _RecordingCondition(threading.Condition):
    """The executor's condition, recording whether each sleep ended by a notify (True) or its
    timeout (False)."""

    def __init__(self, lock: threading.Lock) -> None:
        super().__init__(lock)
        self.ends: list[bool] = []

    def wait(self, timeout: float | None = None) -> bool:
        woken = super().wait(timeout)
        self.ends.append(woken)
        return woken


def spin(spins: int) -> None:
    """A few microseconds' work, so each side starts at a different point of the other's path."""
    for _ in range(spins):
        pass


@pytest.fixture(autouse=True)
def fine_switches() -> Iterator[None]:
    """The interpreter hands its lock between the two threads every microsecond (not every 5 ms),
    so the rounds stop each side at many different points of the other's path."""
    interval = sys.getswitchinterval()
    sys.setswitchinterval(1e-6)
    try:
        yield
    finally:
        sys.setswitchinterval(interval)


def racer(go: threading.Event, spins: int, then: Callable[[], object]) -> threading.Thread:
    """A thread that, once ``go`` is set, works ``spins`` and calls ``then``."""

    def run() -> None:
        go.wait(LONG_S)
        spin(spins)
        then()

    thread = threading.Thread(target=run)
    thread.start()
    return thread


def test_a_wake_from_another_thread_ends_the_executors_sleep_at_every_interleaving() -> None:
    executor = BlockingExecutor(Bus(SystemClock()))
    recording = _RecordingCondition(executor._cv_lock)
    executor._cv = recording
    for i in range(ROUNDS):
        go = threading.Event()
        waker = racer(go, i * 7 % 400, executor.wake)
        go.set()
        spin(i * 97 % 20000)
        executor.spin_once(LONG_S)  # nothing is due: it sleeps until the wake, unless it came first
        waker.join()
    assert recording.ends, "the executor never slept: the race was not run"
    assert all(recording.ends), f"{recording.ends.count(False)} sleeps ran to their timeout"
    # Without a sleeper a wake notifies no one, and the next wait still sees it (the flag).
    before = len(recording.ends)
    executor.wake()
    executor.spin_once(LONG_S)
    assert len(recording.ends) == before


def wait_into(future: Future[int], ended: list[bool]) -> None:
    ended.append(future.wait(LONG_S))


def test_a_future_set_on_one_thread_ends_a_wait_begun_on_another_at_every_interleaving() -> None:
    for i in range(ROUNDS):
        future: Future[int] = Future()
        ended: list[bool] = []
        go = threading.Event()
        waiter = racer(go, i * 7 % 400, functools.partial(wait_into, future, ended))
        go.set()
        spin(i * 37 % 4000)
        future.set_result(i)
        waiter.join(2 * LONG_S)
        assert ended == [True], f"round {i}: the wait ended {ended}"
    done: Future[int] = Future()
    done.set_result(1)
    assert done.wait(0) is True  # done before anyone waited
    assert Future().wait(0.01) is False  # never done: the timeout, as threading.Event's
