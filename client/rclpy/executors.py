"""rclpy's executors for a node process.

An executor spins the nodes added to it (``_executor.py``: each round, tasks in progress, a wait
on the context's wait set, then each ready entity whose callback group lets it run, as a Task).
``SingleThreadedExecutor`` runs each task on the spinning thread, ``MultiThreadedExecutor`` on a
pool of threads; a custom executor subclasses ``Executor`` and overrides ``spin_once`` with
``wait_for_ready_callbacks``, as rclpy's examples do.
"""

from __future__ import annotations

import os
import threading
import warnings
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from typing import Any

from rclpy._context import Context
from rclpy._executor import (
    ConditionReachedException,
    Executor,
    ExternalShutdownException,
    Handler,
    ShutdownException,
    TimeoutException,
    TimeoutObject,
    _never,
    await_or_execute,
)
from rclpy.task import Future, Task

# Named as rclpy names them (a traceback says rclpy.executors.ExternalShutdownException).
for _public in (
    ConditionReachedException,
    Executor,
    ExternalShutdownException,
    ShutdownException,
    TimeoutException,
    TimeoutObject,
):
    _public.__module__ = __name__


class SingleThreadedExecutor(Executor):
    """Runs every callback on the thread that spins, one at a time."""

    def _spin_once_impl(
        self, timeout_sec: float | TimeoutObject | None = None, wait_condition: Callable[[], bool] = _never
    ) -> None:
        try:
            handler, _entity, _node = self.wait_for_ready_callbacks(timeout_sec, None, wait_condition)
        except (ShutdownException, TimeoutException, ConditionReachedException):
            return
        handler()
        exception = handler.exception()
        if exception is not None:
            raise exception
        handler.result()

    def spin_once(self, timeout_sec: float | None = None) -> None:
        self._spin_once_impl(timeout_sec)

    def _spin_once_until_future_complete(
        self, future: Future[Any], timeout_sec: float | TimeoutObject | None = None
    ) -> None:
        self._spin_once_impl(timeout_sec, future.done)

    def spin_once_until_future_complete(
        self, future: Future[Any], timeout_sec: float | TimeoutObject | None = None
    ) -> None:
        future.add_done_callback(lambda _done: self.wake())  # a task of its own, as in rclpy
        self._spin_once_until_future_complete(future, timeout_sec)


class MultiThreadedExecutor(Executor):
    """Runs callbacks on a pool of threads (one per CPU this process may use, unless told):
    a mutually exclusive group's one at a time, a reentrant group's side by side. An exception
    in a callback comes out of ``spin`` on the spinning thread, as in rclpy."""

    def __init__(self, num_threads: int | None = None, *, context: Context | None = None) -> None:
        super().__init__(context=context)
        if num_threads is None:
            affinity = getattr(os, "sched_getaffinity", None)
            num_threads = len(affinity(0)) if affinity is not None else (os.cpu_count() or 2)
        if num_threads == 1:
            warnings.warn(
                "MultiThreadedExecutor is used with a single thread.\nUse the SingleThreadedExecutor instead.",
                stacklevel=2,
            )
        self._futures: list[Task[Any]] = []
        self._executor = ThreadPoolExecutor(num_threads, thread_name_prefix="rclpy-cb")
        self._queued: set[int] = set()  # tasks handed to the pool that no thread has started
        self._queued_lock = threading.Lock()

    def _run(self, handler: Task[Any]) -> None:
        with self._queued_lock:
            self._queued.discard(id(handler))
        handler()

    def _spin_once_impl(
        self, timeout_sec: float | TimeoutObject | None = None, wait_condition: Callable[[], bool] = _never
    ) -> None:
        try:
            handler, _entity, _node = self.wait_for_ready_callbacks(timeout_sec, None, wait_condition)
        except (ExternalShutdownException, ShutdownException, TimeoutException, ConditionReachedException):
            return
        with self._queued_lock:
            if id(handler) in self._queued:
                return  # handed out again before a thread got to it: once is enough
            self._queued.add(id(handler))
        try:
            self._executor.submit(self._run, handler)
        except RuntimeError:  # shut down from another thread while this one handed work out
            if not self._is_shutdown:
                raise
            return
        if handler not in self._futures:
            self._futures.append(handler)
        for future in self._futures[:]:
            if future.done():
                self._futures.remove(future)
                future.result()  # what a callback raised comes out here

    def spin_once(self, timeout_sec: float | None = None) -> None:
        self._spin_once_impl(timeout_sec)

    def _spin_once_until_future_complete(
        self, future: Future[Any], timeout_sec: float | TimeoutObject | None = None
    ) -> None:
        self._spin_once_impl(timeout_sec, future.done)

    def spin_once_until_future_complete(
        self, future: Future[Any], timeout_sec: float | TimeoutObject | None = None
    ) -> None:
        future.add_done_callback(lambda _done: self.wake())  # a task of its own, as in rclpy
        self._spin_once_until_future_complete(future, timeout_sec)

    def shutdown(self, timeout_sec: float | None = None, *, wait_for_threads: bool = True) -> bool:
        done = super().shutdown(timeout_sec)
        self._executor.shutdown(wait=wait_for_threads)
        return done


__all__ = [
    "ConditionReachedException",
    "Executor",
    "ExternalShutdownException",
    "Handler",
    "MultiThreadedExecutor",
    "ShutdownException",
    "SingleThreadedExecutor",
    "TimeoutException",
    "TimeoutObject",
    "await_or_execute",
]
