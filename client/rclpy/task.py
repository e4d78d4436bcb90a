"""rclpy's Future and Task: a result that arrives later, and a function or coroutine an executor runs.

A Future that belongs to an executor (a Task, a service client's response, ``create_future()``)
has its done callbacks run by that executor as tasks of their own, after the step that completed
it; one that belongs to none runs them at once, as rclpy does. ``await future`` inside an ``async
def`` callback or task parks the coroutine until the future is done; the executor resumes it then
and meanwhile runs everything else.
"""

from __future__ import annotations

import inspect
import sys
import threading
import warnings
import weakref
from collections.abc import Callable, Coroutine, Generator
from enum import Enum
from types import CoroutineType, FunctionType
from typing import TYPE_CHECKING, Any, TypeVar

from node_runtime.bus import Future as BusFuture

if TYPE_CHECKING:
    from rclpy.executors import Executor

T = TypeVar("T")


class _Unretrieved:
    """The exception a future was finished with, and whether anyone has fetched it."""

    __slots__ = ("exc", "fetched")

    def __init__(self, exc: BaseException) -> None:
        self.exc, self.fetched = exc, False


def _report_unretrieved(box: _Unretrieved) -> None:
    if not box.fetched:
        print(f"The following exception was never retrieved: {box.exc}", file=sys.stderr)


class FutureState(Enum):
    PENDING = "PENDING"
    CANCELLED = "CANCELLED"
    FINISHED = "FINISHED"


class Future(BusFuture[T]):
    """rclpy 9's Future: ``done()`` only once finished (a cancelled future is not done)."""

    def __init__(self, *, executor: Executor | None = None) -> None:
        super().__init__()
        self._lock = threading.Lock()
        self._unretrieved: _Unretrieved | None = None
        self._executor_ref: Callable[[], Executor | None] = _no_executor
        self._wakers: list[Callable[[], None]] = []
        self._set_executor(executor)

    def __await__(self) -> Generator[Any, None, T | None]:
        while self._pending():
            yield self  # the task that awaits learns what it waits for, and sleeps until it is done
        return self.result()

    def _pending(self) -> bool:
        return not self._done

    @property
    def state(self) -> FutureState:
        if not self._done:
            return FutureState.PENDING
        return FutureState.CANCELLED if self._cancelled else FutureState.FINISHED

    def done(self) -> bool:
        return self._done and not self._cancelled

    def exception(self) -> BaseException | None:
        if self._unretrieved is not None:
            self._unretrieved.fetched = True
        return self._exception

    def result(self) -> T | None:
        exception = self.exception()
        if exception is not None:
            raise exception
        return self._result

    def set_result(self, result: T) -> None:
        with self._lock:
            if self._done:
                return
            self._result = result
            self._done = True
        self._finish()

    def set_exception(self, exc: BaseException) -> None:
        with self._lock:
            if self._done:
                return
            self._exception = exc
            self._done = True
            # As rclpy, a future collected with an exception nobody fetched says so. Only such a
            # future gets a finaliser: a ``__del__`` on every future (a task per callback, ten a
            # second in a 10 Hz node) could swallow a Ctrl-C that lands while it runs, as CPython
            # drops an exception raised in a finaliser ("Exception ignored in").
            self._unretrieved = _Unretrieved(exc)
            weakref.finalize(self, _report_unretrieved, self._unretrieved)
        self._finish()

    def cancel(self) -> None:
        with self._lock:
            if self._done:
                return
            self._cancelled = True
            self._done = True
        self._finish()

    def _finish(self) -> None:
        self._set_event()
        with self._lock:
            callbacks, self._callbacks = self._callbacks, []
            wakers, self._wakers = self._wakers, []
        executor = self._executor_ref()
        for callback in callbacks:
            if executor is not None:
                executor.create_task(callback, self)
                continue
            try:
                callback(self)
            except Exception as exc:  # the other callbacks still run, as in rclpy
                warnings.warn(f"Unhandled exception in done callback: {exc}", stacklevel=2)
        for wake in wakers:
            wake()

    def _set_executor(self, executor: Executor | None) -> None:
        self._executor_ref = _no_executor if executor is None else weakref.ref(executor)

    def add_done_callback(self, callback: Callable[[Future[T]], Any]) -> None:
        with self._lock:
            if not self._done:
                self._callbacks.append(callback)  # type: ignore[arg-type]
                return
        executor = self._executor_ref()
        if executor is not None:
            executor.create_task(callback, self)
        else:
            callback(self)

    def remove_done_callback(self, callback: Callable[[Future[T]], Any]) -> bool:
        with self._lock:
            try:
                self._callbacks.remove(callback)  # type: ignore[arg-type]
            except ValueError:
                return False
            return True

    def _add_waker(self, wake: Callable[[], None]) -> None:
        """Call ``wake`` (on the thread that completes it) once done; at once if it already is."""
        with self._lock:
            if not self._done:
                self._wakers.append(wake)
                return
        wake()


def _is_coroutine_function(fn: Any) -> bool:
    """``inspect.iscoroutinefunction``, answered without its calls for a plain ``async def`` (the
    executor's handler, a task for each callback)."""
    if type(fn) is FunctionType and fn.__code__.co_flags & inspect.CO_COROUTINE:
        return True
    return inspect.iscoroutinefunction(fn)


def _no_executor() -> None:
    return None


def wake_when_done(future: Any, wake: Callable[[], None]) -> None:
    """``wake()`` once ``future`` (ours, or the bus's) is done."""
    if isinstance(future, Future):
        future._add_waker(wake)
    else:
        future.add_done_callback(lambda _done: wake())


class Task(Future[T]):
    """Runs a function, or a coroutine step by step, each time the executor calls it."""

    def __init__(
        self,
        handler: Callable[..., Any],
        args: tuple[Any, ...] | None = None,
        kwargs: dict[str, Any] | None = None,
        executor: Executor | None = None,
    ) -> None:
        super().__init__(executor=executor)
        self._args: tuple[Any, ...] | None = tuple(args or ())
        self._kwargs: dict[str, Any] | None = dict(kwargs or {})
        self._handler: Any = handler
        if _is_coroutine_function(handler):
            self._handler = handler(*self._args, **self._kwargs)
            self._args = self._kwargs = None
        self._executing = False
        self._task_lock = threading.Lock()
        self._awaiting: Any = None  # the future the coroutine waits for, while it is not done

    def __call__(self) -> None:
        """Run the function, or the coroutine up to its next wait; keep what it returned or raised."""
        if not self._pending() or self._executing or not self._task_lock.acquire(blocking=False):
            return
        try:
            if not self._pending():
                return
            self._executing = True
            if isinstance(self._handler, CoroutineType):  # inspect.iscoroutine, without its call
                self._step(self._handler)
            else:
                try:
                    self.set_result(self._handler(*(self._args or ()), **(self._kwargs or {})))
                except Exception as exc:
                    self.set_exception(exc)
                self._complete_task()
            self._executing = False
        finally:
            self._task_lock.release()

    def _step(self, coroutine: Coroutine[Any, Any, Any]) -> None:
        try:
            awaited = coroutine.send(None)
        except StopIteration as stop:
            self.set_result(stop.value)
            self._complete_task()
        except Exception as exc:
            self.set_exception(exc)
            self._complete_task()
        else:
            self._park(awaited)

    def _park(self, awaited: Any) -> None:
        if not isinstance(awaited, BusFuture) or awaited.done() or awaited.cancelled():
            self._awaiting = None  # a bare yield: runs again at the executor's next look
            return
        self._awaiting = awaited
        executor = self._executor_ref()
        wake_when_done(awaited, executor.wake if executor is not None else _nothing)

    def _resumable(self) -> bool:
        awaiting = self._awaiting
        return awaiting is None or awaiting.done() or awaiting.cancelled()

    def _complete_task(self) -> None:
        self._handler = self._args = self._kwargs = None
        self._awaiting = None

    def executing(self) -> bool:
        return self._executing

    def cancel(self) -> None:
        if self._pending() and isinstance(self._handler, CoroutineType):
            self._handler.close()
        super().cancel()


def _nothing() -> None:
    pass


__all__ = ["Future", "FutureState", "Task"]
