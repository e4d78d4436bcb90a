"""rclpy's executors for a node process. Every node of the process lives on one bus, so an executor
spins them all; ``add_node`` is kept for rclpy's API (and ``get_nodes`` reports what was added)."""

from __future__ import annotations

import threading
from concurrent.futures import ThreadPoolExecutor
from typing import Any

from server.bus import Future, Node
from server.bus.blocking import BlockingExecutor

from ._context import Context, default_context


class ExternalShutdownException(Exception):
    """The context was shut down (by ``rclpy.shutdown()`` from another thread) while spinning."""


class TimeoutException(Exception):
    """``spin_once`` with a timeout that passed without work (rclpy's, for its callers)."""


class Executor:
    """Spins the process's nodes: timers, subscriptions and service calls, one callback at a time."""

    def __init__(self, *, context: Context | None = None) -> None:
        self.context = context or default_context
        self._nodes: list[Node] = []
        self._shut_down = False

    def _core(self) -> BlockingExecutor:
        _bus, executor = self.context.require()
        return executor

    def add_node(self, node: Node) -> bool:
        if node in self._nodes:
            return False
        self._nodes.append(node)
        return True

    def remove_node(self, node: Node) -> None:
        if node in self._nodes:
            self._nodes.remove(node)

    def get_nodes(self) -> list[Node]:
        return list(self._nodes)

    def _check(self) -> None:
        if not self.context.ok() or self._shut_down:
            raise ExternalShutdownException("the context was shut down")

    def spin_once(self, timeout_sec: float | None = None) -> None:
        self._check()
        self._core().spin_once(timeout_sec)

    def spin(self) -> None:
        """Until the context shuts down; Ctrl-C raises KeyboardInterrupt here, as in rclpy."""
        while self.context.ok() and not self._shut_down:
            self._core().spin_once(None)
        self._check()

    def spin_until_future_complete(self, future: Future[Any], timeout_sec: float | None = None) -> None:
        self._check()
        self._core().run_until(future.done, timeout_sec)

    def shutdown(self, timeout_sec: float | None = None) -> bool:
        self._shut_down = True
        if self.context.ok():
            self._core().wake()
        return True


class SingleThreadedExecutor(Executor):
    pass


class MultiThreadedExecutor(Executor):
    """Callbacks run on a pool of threads. A node's callbacks never run at the same time as each other
    (rclpy's default, a mutually exclusive callback group per node); different nodes' may."""

    def __init__(self, num_threads: int | None = None, *, context: Context | None = None) -> None:
        super().__init__(context=context)
        self._pool = ThreadPoolExecutor(max_workers=num_threads or 4, thread_name_prefix="rclpy-cb")
        self._node_locks: dict[int, threading.Lock] = {}
        self._error: BaseException | None = None
        self._installed = False

    def _install(self) -> None:
        core = self._core()
        if self._installed:
            return
        self._installed = True

        def run(node: Node, fn: Any, *args: Any) -> None:
            lock = self._node_locks.setdefault(id(node), threading.Lock())

            def task() -> None:
                with lock:
                    try:
                        fn(*args)
                    except BaseException as exc:  # handed to the spinning thread, as rclpy does
                        self._error = exc
                        core.wake()

            self._pool.submit(task)
            core.callbacks_run += 1

        core._run = run  # type: ignore[method-assign]

    def _raise_pending(self) -> None:
        error, self._error = self._error, None
        if error is not None:
            raise error

    def spin_once(self, timeout_sec: float | None = None) -> None:
        self._install()
        super().spin_once(timeout_sec)
        self._raise_pending()

    def spin(self) -> None:
        self._install()
        while self.context.ok() and not self._shut_down:
            self._core().spin_once(None)
            self._raise_pending()
        self._check()

    def spin_until_future_complete(self, future: Future[Any], timeout_sec: float | None = None) -> None:
        self._install()
        super().spin_until_future_complete(future, timeout_sec)
        self._raise_pending()

    def shutdown(self, timeout_sec: float | None = None) -> bool:
        super().shutdown(timeout_sec)
        self._pool.shutdown(wait=timeout_sec is None or timeout_sec > 0)
        return True


__all__ = [
    "Executor",
    "ExternalShutdownException",
    "MultiThreadedExecutor",
    "SingleThreadedExecutor",
    "TimeoutException",
]
