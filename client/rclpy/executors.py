"""rclpy's executors for a node process.

Every node of the process lives on one bus; an executor collects what is ready on it (messages,
due timers, service requests, triggered guard conditions) as handlers and runs them: one at a
time on the spinning thread (SingleThreadedExecutor), or on a pool of threads with each callback
group's rule (MultiThreadedExecutor). A custom executor subclasses ``Executor`` and overrides
``spin_once`` with ``wait_for_ready_callbacks``, as rclpy's examples do.
"""

from __future__ import annotations

import threading
import time
from collections import deque
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from typing import Any

from server.bus import Future, Node
from server.bus.blocking import BlockingExecutor
from server.bus.services import PendingCall

from ._context import Context, default_context
from .callback_groups import CallbackGroup, MutuallyExclusiveCallbackGroup


class ExternalShutdownException(Exception):
    """The context was shut down (by ``rclpy.shutdown()`` from another thread) while spinning."""


class ShutdownException(Exception):
    """The executor was shut down while waiting."""


class TimeoutException(Exception):
    """``wait_for_ready_callbacks`` with a timeout that passed without work."""


class Handler:
    """One ready callback: call it to run it; ``result()`` re-raises what it raised."""

    def __init__(self, node: Node, fn: Callable[..., Any], args: tuple[Any, ...]) -> None:
        self.node = node
        self._fn = fn
        self._args = args
        self._error: BaseException | None = None
        group = getattr(fn, "callback_group", None)
        self.callback_group: CallbackGroup = (
            group or getattr(node, "default_callback_group", None) or _FALLBACK
        )

    def __call__(self) -> None:
        try:
            self._fn(*self._args)
        except BaseException as exc:
            self._error = exc
            raise

    def result(self) -> None:
        if self._error is not None:
            raise self._error


_FALLBACK = MutuallyExclusiveCallbackGroup()  # the lab's own bus nodes have no group of their own


class Executor:
    """Spins the process's nodes; ``add_node`` is kept for rclpy's API (``get_nodes`` reports it)."""

    def __init__(self, *, context: Context | None = None) -> None:
        self.context = context or default_context
        self._nodes: list[Node] = []
        self._shut_down = False
        self._waiting: deque[Handler] = deque()
        self._collect_lock = threading.Lock()

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
        if not self.context.ok():
            raise ExternalShutdownException("the context was shut down")
        if self._shut_down:
            raise ShutdownException("the executor was shut down")

    # -- collecting ----------------------------------------------------------------------------
    def _collect(self, timeout_sec: float | None) -> list[Handler]:
        """What became ready within ``timeout_sec`` (None: wait for something), not yet run."""
        core = self._core()
        got: list[Handler] = []

        def capture(node: Node, fn: Callable[..., Any], *args: Any) -> None:
            got.append(Handler(node, fn, args))
            core.callbacks_run += 1

        def capture_call(call: PendingCall) -> bool:
            server = call.server
            if not server.active:
                return False  # the server went away: the client keeps waiting, as in ROS 2

            def answer() -> None:
                server.answer(call)

            answer.callback_group = getattr(server.callback, "callback_group", None)  # type: ignore[attr-defined]
            got.append(Handler(server.node, answer, ()))
            return True

        with self._collect_lock:
            core._run = capture  # type: ignore[method-assign]
            core._run_call = capture_call  # type: ignore[method-assign]
            try:
                core.spin_once(timeout_sec)
            finally:
                del core._run, core._run_call
        return got

    def wait_for_ready_callbacks(self, timeout_sec: float | None = None) -> tuple[Handler, Any, Node]:
        """The next ready callback as (handler, entity's group, node); raises TimeoutException."""
        if not self._waiting:
            self._check()
            self._waiting.extend(self._collect(timeout_sec))
        if not self._waiting:
            self._check()
            raise TimeoutException(f"nothing became ready within {timeout_sec} s")
        handler = self._waiting.popleft()
        return handler, handler.callback_group, handler.node

    # -- spinning ------------------------------------------------------------------------------
    def _dispatch(self, handler: Handler) -> None:
        handler()

    def spin_once(self, timeout_sec: float | None = None) -> None:
        try:
            handler, _group, _node = self.wait_for_ready_callbacks(timeout_sec)
        except TimeoutException:
            return
        self._dispatch(handler)

    def spin(self) -> None:
        """Until the context shuts down; Ctrl-C raises KeyboardInterrupt here, as in rclpy."""
        try:
            while not self._shut_down:
                self.spin_once(None)
        except ShutdownException:
            pass  # this executor's shutdown() ends its spin quietly; the context's raises
        if not self.context.ok():
            raise ExternalShutdownException("the context was shut down")

    def spin_until_future_complete(self, future: Future[Any], timeout_sec: float | None = None) -> None:
        end = None if timeout_sec is None or timeout_sec < 0 else time.monotonic() + timeout_sec
        while not future.done() and not self._shut_down:
            left = None if end is None else end - time.monotonic()
            if left is not None and left <= 0:
                return
            try:
                self.spin_once(left)
            except ShutdownException:
                return

    def shutdown(self, timeout_sec: float | None = None) -> bool:
        self._shut_down = True
        if self.context.ok():
            self._core().wake()
        return True


class SingleThreadedExecutor(Executor):
    """Runs every callback on the spinning thread, one at a time."""


class MultiThreadedExecutor(Executor):
    """Callbacks run on a pool of threads: a mutually exclusive group's one at a time and in the
    order they became ready, a reentrant group's in parallel. The spinning thread only collects
    (and so keeps answering the Zenoh side: a synchronous service call from a callback completes)."""

    def __init__(self, num_threads: int | None = None, *, context: Context | None = None) -> None:
        super().__init__(context=context)
        self._pool = ThreadPoolExecutor(max_workers=num_threads or 4, thread_name_prefix="rclpy-cb")
        self._lock = threading.Lock()
        self._queues: dict[int, deque[Handler]] = {}
        self._error: BaseException | None = None

    def _run_caught(self, handler: Handler) -> None:
        try:
            handler()
        except BaseException as exc:  # handed to the spinning thread, as rclpy does
            self._error = exc
            if self.context.bus is not None:
                self.context.bus.wake_threadsafe()

    def _drain_group(self, key: int) -> None:
        while True:
            with self._lock:
                queue = self._queues[key]
                if not queue:
                    del self._queues[key]
                    return
                handler = queue[0]
            self._run_caught(handler)
            with self._lock:
                queue.popleft()

    def _submit(self, fn: Callable[..., None], arg: Any) -> None:
        try:
            self._pool.submit(fn, arg)
        except RuntimeError:  # shut down from another thread while this one handed work out
            if not self._shut_down:
                raise

    def _dispatch(self, handler: Handler) -> None:
        group = handler.callback_group
        if not isinstance(group, MutuallyExclusiveCallbackGroup):
            self._submit(self._run_caught, handler)
            return
        key = id(group)
        with self._lock:
            queue = self._queues.get(key)
            if queue is not None:
                queue.append(handler)  # its drainer runs it after the ones before it
                return
            self._queues[key] = deque([handler])
        self._submit(self._drain_group, key)

    def _raise_pending(self) -> None:
        error, self._error = self._error, None
        if error is not None:
            raise error

    def spin_once(self, timeout_sec: float | None = None) -> None:
        self._raise_pending()
        while True:  # hand out everything ready now, not one per wake-up
            try:
                handler, _group, _node = self.wait_for_ready_callbacks(timeout_sec)
            except TimeoutException:
                break
            self._dispatch(handler)
            if not self._waiting:
                break
        self._raise_pending()

    def shutdown(self, timeout_sec: float | None = None) -> bool:
        super().shutdown(timeout_sec)
        self._pool.shutdown(wait=timeout_sec is None or timeout_sec > 0)
        return True


__all__ = [
    "Executor",
    "ExternalShutdownException",
    "Handler",
    "MultiThreadedExecutor",
    "ShutdownException",
    "SingleThreadedExecutor",
    "TimeoutException",
]
