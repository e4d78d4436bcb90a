"""rclpy's Executor base: what every executor shares (its nodes, tasks, shutdown, spinning) and
``wait_for_ready_callbacks``, which hands out the work of a round: tasks in progress first, then a
wait on the context's wait set (``_wait_set.py``), then each ready entity of the executor's nodes
whose callback group lets it run, in rclpy's order, as a Task that asks the group
(``beginning_execution``), runs the callback (awaiting it if it is ``async def``) and tells the
group it ended. ``executors.py`` builds the single- and multi-threaded executors on it.
"""

from __future__ import annotations

import contextlib
import threading
import time
from collections.abc import Callable, Generator
from typing import Any, cast

from node_runtime.bus import Node
from rclpy._context import Context, default_context
from rclpy._wait_set import Ready, WaitSet, is_async
from rclpy.task import Future, Task

Handler = Task  # what wait_for_ready_callbacks hands out: call it to run (or resume) the callback
Yielded = tuple[Task[Any], Any, Any]


async def await_or_execute(callback: Callable[..., Any], *args: Any) -> Any:
    """Await ``callback(*args)`` if ``callback`` is ``async def``, else just call it."""
    if is_async(callback):
        return await callback(*args)
    return callback(*args)


class TimeoutException(Exception):
    """``wait_for_ready_callbacks`` with a timeout that passed without work."""


class ShutdownException(Exception):
    """The executor was shut down while waiting."""


class ExternalShutdownException(Exception):
    """The context was shut down (by ``rclpy.shutdown()`` from another thread) while spinning."""


class ConditionReachedException(Exception):
    """The condition ``wait_for_ready_callbacks`` was given became true (a future is done)."""


class TimeoutObject:
    """A timeout the caller shortens between calls (``spin_until_future_complete``'s)."""

    def __init__(self, timeout: float) -> None:
        self.timeout = timeout


class _WorkTracker:
    """How many callbacks are running, so ``shutdown`` can wait for them."""

    def __init__(self) -> None:
        self._running = 0
        self._waiting = 0  # threads in wait(): a callback's end notifies only when there are any
        self._lock = threading.Lock()
        self._idle = threading.Condition(self._lock)

    def __enter__(self) -> None:
        with self._lock:
            self._running += 1

    def __exit__(self, *_exc: object) -> None:
        with self._lock:
            self._running -= 1
            if self._waiting and not self._running:
                self._idle.notify_all()

    def wait(self, timeout_sec: float | None = None) -> bool:
        if timeout_sec is not None and timeout_sec < 0:
            timeout_sec = None
        with self._lock:
            self._waiting += 1
            try:
                return self._idle.wait_for(lambda: self._running == 0, timeout_sec)
            finally:
                self._waiting -= 1


def _never() -> bool:
    return False


def _ranking(nodes: list[Node]) -> Callable[[Ready], tuple[int, int, int, int]]:
    """rclpy's order within a round: the actions' entities (its waitables) of every node first,
    then node by node its timers, subscriptions, guard conditions, clients and services, each
    kind in the order the node made them. (An action client's feedback comes before its result
    here: rclpy takes both in one callback, so a result never overtakes the feedback before it.)"""
    where: dict[int, int] = {}  # filled at the first comparison: a round of one needs none

    def rank(ready: Ready) -> tuple[int, int, int, int]:
        if not where:
            where.update((id(node), i) for i, node in enumerate(nodes))
        waitable, kind, index = ready.place()
        return (waitable, where.get(id(ready.node), len(where)), kind, index)

    return rank


class Executor:
    """The base of every executor; a subclass defines ``spin_once``."""

    def __init__(self, *, context: Context | None = None) -> None:
        self._context = context or default_context
        self._nodes: list[Node] = []
        self._nodes_lock = threading.RLock()
        self._tasks: list[Yielded] = []
        self._tasks_lock = threading.Lock()
        self._is_shutdown = False
        self._shutdown_lock = threading.Lock()
        self._work_tracker = _WorkTracker()
        self._cb_iter: Generator[Yielded, None, None] | None = None
        self._last_args: tuple[Any, ...] | None = None
        self._last_kwargs: dict[str, Any] | None = None

    @property
    def context(self) -> Context:
        return self._context

    def _wait_set(self) -> WaitSet:
        wait_set = self._context.executor
        if not self._context.ok() or wait_set is None:
            raise ExternalShutdownException("the context was shut down")
        return cast(WaitSet, wait_set)

    def _spinning(self) -> contextlib.AbstractContextManager[None]:
        wait_set = self._context.executor
        return wait_set.spinning() if isinstance(wait_set, WaitSet) else contextlib.nullcontext()

    # -- work ----------------------------------------------------------------------------------
    def create_task(self, callback: Callable[..., Any], *args: Any, **kwargs: Any) -> Task[Any]:
        """Run ``callback`` (a function or an ``async def``) while spinning; a Future of its result."""
        task: Task[Any] = Task(callback, args, kwargs, executor=self)
        with self._tasks_lock:
            self._tasks.append((task, None, None))
        self.wake()
        return task

    def create_future(self) -> Future[Any]:
        return Future(executor=self)

    def wake(self) -> None:
        """Have the executor look again (a task was created, a group let go of a callback)."""
        wait_set = self._context.executor
        if isinstance(wait_set, WaitSet):
            wait_set.wake()

    # -- nodes ---------------------------------------------------------------------------------
    def add_node(self, node: Node) -> bool:
        with self._nodes_lock:
            if node in self._nodes:
                return False
            self._nodes.append(node)
        if getattr(node, "executor", None) is not self:
            node.executor = self  # type: ignore[attr-defined]  # rclpy's Node moves to this executor
        self.wake()
        return True

    def remove_node(self, node: Node) -> None:
        with self._nodes_lock:
            if node not in self._nodes:
                return
            self._nodes.remove(node)
        self.wake()

    def get_nodes(self) -> list[Node]:
        with self._nodes_lock:
            return list(self._nodes)

    def shutdown(self, timeout_sec: float | None = None) -> bool:
        """Stop executing callbacks. rclpy 9 does not wait for those running (its check comes
        after the flag it checks is set), so neither does this: it returns True."""
        with self._shutdown_lock:
            first = not self._is_shutdown
            self._is_shutdown = True
        if first:
            self.wake()
        with self._nodes_lock:
            self._nodes = []
        self._cb_iter = None
        self._last_args = self._last_kwargs = None
        return True

    def __enter__(self) -> Executor:
        return self

    def __exit__(self, *_exc: object) -> None:
        self.shutdown()

    # -- spinning ------------------------------------------------------------------------------
    def spin(self) -> None:
        """Until the context or this executor shuts down; Ctrl-C raises KeyboardInterrupt, as in rclpy."""
        with self._spinning():
            while self._context.ok() and not self._is_shutdown:
                self.spin_once()

    def spin_until_future_complete(self, future: Future[Any], timeout_sec: float | None = None) -> None:
        """Until ``future`` is done (or cancelled), the context shuts down or ``timeout_sec`` passes."""
        future.add_done_callback(lambda _done: self.wake())  # a task of its own, as in rclpy

        def waiting() -> bool:
            return (
                self._context.ok() and not future.done() and not future.cancelled() and not self._is_shutdown
            )

        with self._spinning():
            self._spin_until(future, timeout_sec, waiting)

    def _spin_until(
        self, future: Future[Any], timeout_sec: float | None, waiting: Callable[[], bool]
    ) -> None:
        if timeout_sec is None or timeout_sec < 0:
            while waiting():
                self._spin_once_until_future_complete(future, timeout_sec)
            return
        end = time.monotonic() + timeout_sec
        left = TimeoutObject(timeout_sec)
        while waiting():
            self._spin_once_until_future_complete(future, left)
            now = time.monotonic()
            if now >= end:
                return
            left.timeout = end - now

    def spin_once(self, timeout_sec: float | None = None) -> None:
        """Wait for and run one callback; what a custom executor overrides."""
        raise NotImplementedError()

    def spin_once_until_future_complete(
        self, future: Future[Any], timeout_sec: float | TimeoutObject | None = None
    ) -> None:
        raise NotImplementedError()

    def _spin_once_until_future_complete(
        self, future: Future[Any], timeout_sec: float | TimeoutObject | None = None
    ) -> None:
        raise NotImplementedError()

    # -- handing out work ----------------------------------------------------------------------
    def can_execute(self, entity: Any) -> bool:
        group = getattr(entity, "callback_group", None)
        return group is None or bool(group.can_execute(entity))

    def _make_handler(self, ready: Ready, wait_set: WaitSet) -> Task[None]:
        """The task that runs ``ready``'s callback, if its group lets it when the task starts."""

        async def handler() -> None:
            if self._is_shutdown or not ready.group.beginning_execution(ready.entity):
                wait_set.put_back(ready)  # not taken: it stays ready, as an entity does in rclpy
                return
            with self._work_tracker:
                wait_set.started(ready)
                try:
                    work = ready.run()
                    if work is not None:
                        await work
                finally:
                    ready.group.ending_execution(ready.entity)
                    self.wake()  # the group may let the next one in

        task: Task[None] = Task(handler, executor=self)
        with self._tasks_lock:
            self._tasks.append((task, ready.entity, ready.node))
        return task

    def _wait_for_ready_callbacks(
        self,
        timeout_sec: float | TimeoutObject | None = None,
        nodes: list[Node] | None = None,
        condition: Callable[[], bool] = _never,
    ) -> Generator[Yielded, None, None]:
        """Tasks in progress first, then a wait, then each ready entity its group lets run; each
        at most once a round. Raises TimeoutException, ShutdownException, ExternalShutdownException,
        or ConditionReachedException once ``condition()``."""
        timeout = timeout_sec.timeout if isinstance(timeout_sec, TimeoutObject) else timeout_sec
        end = None if timeout is None or timeout < 0 else time.monotonic() + timeout
        yielded = False
        while not yielded and not self._is_shutdown and not condition():
            use = self.get_nodes() if nodes is None else list(nodes)
            wait_set = self._wait_set()
            since = wait_set.generation()
            with self._tasks_lock:
                tasks = list(self._tasks)
            for task, entity, node in tasks:
                if task.executing() or not task._pending() or not task._resumable():
                    continue
                if node is None or node in use:
                    yielded = True
                    yield task, entity, node
            with self._tasks_lock:
                self._tasks = [t for t in self._tasks if t[0]._pending()]

            def wanted(ready: Ready, use: list[Node] = use) -> bool:
                return ready.node in use and bool(ready.group.can_execute(ready.entity))

            left = None if end is None else max(0.0, end - time.monotonic())
            wait_set.wait(0.0 if wait_set.any(wanted) else left, since)
            if self._is_shutdown:
                raise ShutdownException()
            if not self._context.ok():
                raise ExternalShutdownException()
            seen: set[int] = set()
            rank = _ranking(use)
            while (ready := wait_set.take(wanted, seen, rank)) is not None:
                yielded = True
                yield self._make_handler(ready, wait_set), ready.entity, ready.node
            if timeout == 0 or (end is not None and time.monotonic() >= end):
                raise TimeoutException()
        if self._is_shutdown:
            raise ShutdownException()
        if condition():
            raise ConditionReachedException()

    def wait_for_ready_callbacks(self, *args: Any, **kwargs: Any) -> Yielded:
        """The next (handler, entity, node) to run; waits as long as ``timeout_sec`` says (None:
        until there is one). Call the handler to run it."""
        while True:
            if self._cb_iter is None or self._last_args != args or self._last_kwargs != kwargs:
                self._last_args, self._last_kwargs = args, kwargs
                self._cb_iter = self._wait_for_ready_callbacks(*args, **kwargs)
            try:
                return next(self._cb_iter)
            except StopIteration:
                self._cb_iter = None
