"""The wait set of a node process: what is ready on the bus, waiting for an executor to take it.

rclpy's executors wait on a wait set and take each ready entity (a subscription with a message, a
due timer, a request for a service, a client's response, a triggered guard condition) when its
callback group lets them. Here the process's bus is waited on by this subclass of the bus's
blocking executor, which runs no callback itself: it records each as a ``Ready`` in one pool per
context, in the order they came. Every executor of the context takes from the pool the ones of
its own nodes, so a node no executor spins runs nothing, as in rclpy.

A subscription, a timer and a guard condition are ready at most once at a time (the message is
taken when its callback starts; what is left makes it ready again), so a group that holds an
entity back holds back one entry, not one per message or period.
"""

from __future__ import annotations

import contextlib
import copy
import inspect
import threading
from collections.abc import Callable, Iterator
from types import CoroutineType
from typing import Any, cast

from node_runtime.bus import Future as BusFuture
from node_runtime.bus import Node, Subscription
from node_runtime.bus.blocking import BlockingExecutor
from node_runtime.bus.graph import Bus
from node_runtime.bus.services import PendingCall, ServiceServer
from rclpy.callback_groups import CallbackGroup, GroupedCallback, MutuallyExclusiveCallbackGroup
from rclpy.task import Future

Run = Callable[[], Any]  # takes the entity's data and runs its callback; an awaitable if it is async
_FALLBACK = MutuallyExclusiveCallbackGroup()  # a lab's built-in node (the bus's) has no group


def is_async(callback: Any) -> bool:
    """rclpy awaits a callback that is a coroutine function (``async def``), and only that."""
    return inspect.iscoroutinefunction(getattr(callback, "callback", callback))


def call(callback: Callable[..., Any], *args: Any) -> Any:
    """Run ``callback``; the coroutine to await if it is ``async def`` (seen through the node's
    wrappers, which hand on what it returns), else None."""
    result = callback(*args)
    return result if isinstance(result, CoroutineType) else None  # inspect.iscoroutine


def group_of(node: Any, callback: Any) -> CallbackGroup:
    group = getattr(callback, "callback_group", None) or getattr(node, "default_callback_group", None)
    return group if isinstance(group, CallbackGroup) else _FALLBACK


class Ready:
    """An entity with work for its callback: ``run()`` takes that work and runs it."""

    __slots__ = ("_place", "entity", "group", "node", "once", "run")

    def __init__(self, node: Any, entity: Any, group: CallbackGroup, run: Run, *, once: bool) -> None:
        self.node, self.entity, self.group, self.run, self.once = node, entity, group, run, once
        self._place: tuple[int, int, int] | None = None

    def place(self) -> tuple[int, int, int]:
        """Where rclpy's round looks at it in its node: (0 for an action's entity, else 1; its
        kind: timer, subscription, guard condition, client, service; its index among them)."""
        if self._place is None:
            node, entity = self.node, self.entity
            self._place = (1, 5, 0)
            kinds = (
                node.timers,
                node.subscriptions,
                getattr(node, "guards", ()),
                node.clients,
                node.services,
            )
            for kind, entities in enumerate(kinds):
                index = next((i for i, e in enumerate(entities) if e is entity), None)
                if index is not None:
                    self._place = (0 if getattr(entity, "in_waitable", False) else 1, kind, index)
                    break
        return self._place


class WaitSet(BlockingExecutor):
    """The bus's executor for a node process: it waits and records; rclpy's executors run."""

    def __init__(self, bus: Bus) -> None:
        super().__init__(bus)
        self._items: list[Ready] = []
        self._once: set[int] = set()  # ids of entities ready at most once, with an entry in _items
        self._lock = threading.Lock()
        self._changed = threading.Condition(self._lock)
        self._generation = 0  # moves on each time the pool may have changed or a wake came
        self._collecting = threading.Lock()
        self._waiters = 0  # threads waiting on _changed (the others wait on the bus)
        self._spinners: dict[int, int] = {}  # thread → how many spin loops it is inside
        self._since: int | None = None  # the generation the collecting thread's round began at

    # -- recording (on the thread that waits, inside the bus's pass) -------------------------
    def add(self, ready: Ready) -> None:
        with self._lock:
            if ready.once:
                key = id(ready.entity)
                if key in self._once:
                    return
                self._once.add(key)
            self._items.append(ready)
            self._generation += 1
            if self._waiters:
                self._changed.notify_all()
        self.wake_core()

    def _run(self, node: Node, fn: Callable[..., Any], *args: Any) -> None:  # a due timer
        timer: Any = fn
        for entity in getattr(node, "timers", ()):
            if entity.callback is fn:
                timer = entity
                break
        self.add(Ready(node, timer, group_of(node, fn), lambda: call(fn, *args), once=True))
        self.callbacks_run += 1

    def _run_subscription(self, sub: Subscription) -> bool:
        if sub.destroyed or sub.node._state != "active" or not sub.queue:
            return False
        self.add_subscription(sub)
        return True

    def add_subscription(self, sub: Subscription) -> None:
        def run() -> Any:
            if sub.destroyed or sub.node._state != "active" or not sub.queue:
                return None
            msg = sub.queue.popleft()
            if sub.queue:  # more came: the subscription is ready again, after what is ready now
                self.add_subscription(sub)
            return call(sub.callback, msg)

        self.add(Ready(sub.node, sub, group_of(sub.node, sub.callback), run, once=True))

    def _run_call(self, pending: PendingCall) -> bool:
        server = pending.server
        if not server.active:
            return False  # the server went away: the client keeps waiting, as in ROS 2
        # Each request is work of its own (a guard condition collapses its triggers itself).
        group = group_of(server.node, server.callback)
        entity = getattr(server, "entity", server)  # a response's: its client
        self.add(Ready(server.node, entity, group, lambda: answer(pending), once=False))
        return True

    # -- taking (any executor's thread) -------------------------------------------------------
    def take(
        self, wanted: Callable[[Ready], bool], seen: set[int], rank: Callable[[Ready], Any]
    ) -> Ready | None:
        """The first ready entry, in ``rank``'s order, that ``wanted`` accepts (its node is the
        executor's, its group lets it run), out of the pool. ``seen``: ids of the entities handed
        out this round, each at most once a round (a subscription ready again waits for the next)."""
        with self._lock:
            candidates = [r for r in self._items if id(r.entity) not in seen]
        if len(candidates) > 1:
            candidates.sort(key=rank)
        for ready in candidates:
            if not wanted(ready):
                continue
            with self._lock:
                if ready not in self._items:
                    continue  # another executor took it meanwhile
                self._items.remove(ready)
            seen.add(id(ready.entity))
            return ready
        return None

    def started(self, ready: Ready) -> None:
        """``ready``'s callback has begun: its entity may be ready again from now on."""
        if ready.once:
            with self._lock:
                self._once.discard(id(ready.entity))

    def put_back(self, ready: Ready) -> None:
        """Its group refused it after all (another callback got in first): ready as before."""
        with self._lock:
            self._items.insert(0, ready)
            self._generation += 1
            if self._waiters:
                self._changed.notify_all()

    def any(self, wanted: Callable[[Ready], bool]) -> bool:
        with self._lock:
            candidates = list(self._items)
        return bool(candidates) and any(wanted(r) for r in candidates)

    # -- waiting ------------------------------------------------------------------------------
    def generation(self) -> int:
        with self._lock:
            return self._generation

    def wait(self, timeout_s: float | None, since: int) -> None:
        """Wait for news (something recorded, a wake) at most ``timeout_s`` (None: 1 s at a time).
        One thread waits on the bus; any other waits for the one that does."""
        if self._collecting.acquire(blocking=False):
            try:
                self._since = since
                self.spin_once(timeout_s)
            finally:
                self._since = None
                self._collecting.release()
                self._bump()
            return
        with self._changed:
            self._waiters += 1
            try:
                self._changed.wait_for(
                    lambda: self._generation != since, 1.0 if timeout_s is None else timeout_s
                )
            finally:
                self._waiters -= 1

    def _has_news(self) -> bool:
        """For the collecting thread, only news that came after its round began: a wake from before
        (its own callbacks' ends, the entries its own pass recorded) is in what the round already
        looked at, and would only cost an idle turn. Every wake bumps the generation before it
        notifies under the bus wait's lock, so none falls between this check and the wait."""
        since = self._since
        return self._woken if since is None else self._generation != since

    @contextlib.contextmanager
    def spinning(self) -> Iterator[None]:
        """Held by a thread while it spins an executor (a rate elsewhere then only sleeps)."""
        ident = threading.get_ident()
        with self._lock:
            self._spinners[ident] = self._spinners.get(ident, 0) + 1
        try:
            yield
        finally:
            with self._lock:
                self._spinners[ident] -= 1
                if not self._spinners[ident]:
                    del self._spinners[ident]

    def spun_elsewhere(self) -> bool:
        ident = threading.get_ident()
        with self._lock:
            return any(t != ident for t in self._spinners) or bool(self.spinning_threads - {ident})

    def wake_core(self) -> None:
        BlockingExecutor.wake(self)

    def wake(self) -> None:
        """Any waiter looks again (a task was created, a group let go, the executor shut down)."""
        self._bump()
        self.wake_core()

    def _bump(self) -> None:
        with self._lock:
            self._generation += 1
            if self._waiters:
                self._changed.notify_all()

    def stop(self) -> None:
        super().stop()
        self._bump()


def answer(pending: PendingCall) -> Any:
    """Answer a request, or run a guard condition or an action's part; the coroutine if async."""
    server = pending.server
    plain = isinstance(server, ServiceServer) and type(server).answer is ServiceServer.answer
    if plain and _is_async_service(server):
        return _answer_async(server, pending)
    result: Any = cast(Any, server).answer(pending)  # a guard's, an action's: maybe a coroutine
    return result if inspect.iscoroutine(result) else None


def _is_async_service(server: ServiceServer) -> bool:
    callback = getattr(server.callback, "callback", server.callback)
    return inspect.iscoroutinefunction(getattr(callback, "__wrapped__", callback))


async def _answer_async(server: ServiceServer, pending: PendingCall) -> None:
    response = await server.callback(pending.request, server.srv_type.Response())
    # The server's own handling (its response's check, its introspection) sees the awaited
    # response, from a copy whose callback gives it: the server is not changed under other threads.
    done = copy.copy(server)
    done.callback = lambda _request, _response: response
    done.answer(pending)


class Response(Future[Any]):
    """A service client's future: the response the bus hands it is work for the client (in its
    callback group, on its node's executor), queued on the bus behind what came before it (the
    feedback an action server published before its result), which completes the future when an
    executor takes it, as rclpy's executor takes a client's response; its done callbacks then run
    as tasks of that executor. With the context gone, it completes at once."""

    def __init__(self, client: Any) -> None:
        super().__init__()
        self._client = client

    def set_result(self, result: Any) -> None:
        node = self._client.node
        context = getattr(node, "_rcl_context", None)
        if self._done or context is None or not context.ok():
            Future.set_result(self, result)
            return
        bus = node._bus
        call = PendingCall(cast(ServiceServer, _Delivery(self, result)), cast(Any, None), BusFuture())
        with bus.lock if bus.lock is not None else contextlib.nullcontext():
            bus.queue_call(call)
        bus.wake_threadsafe()

    def _deliver(self, result: Any) -> None:
        self._set_executor(getattr(self._client.node, "executor", None))
        Future.set_result(self, result)


class _Delivery:
    """A response on its way to its future, queued on the bus as a request is."""

    def __init__(self, future: Response, result: Any) -> None:
        client = future._client
        self.node, self.entity = client.node, client
        self.callback = GroupedCallback(lambda: future._deliver(result), group_of(client.node, client))

    @property
    def active(self) -> bool:
        return not self.entity.destroyed and self.node._state == "active"

    def answer(self, _call: PendingCall) -> None:
        self.callback()
