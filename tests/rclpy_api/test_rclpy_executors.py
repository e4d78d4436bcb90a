"""rclpy's init context manager, executors, callback groups, guard conditions, futures and the
synchronous client, in one process without Zenoh. Waits are bounded and end on a future."""

from __future__ import annotations

import threading
from collections.abc import Iterator
from typing import Any

import pytest
import rclpy
from example_interfaces.srv import AddTwoInts
from rclpy.callback_groups import MutuallyExclusiveCallbackGroup, ReentrantCallbackGroup
from rclpy.executors import Executor, MultiThreadedExecutor, SingleThreadedExecutor, TimeoutException
from rclpy.node import Node
from rclpy.task import Future
from std_msgs.msg import Int64

BOUND_S = 10.0  # every wait ends sooner, on a future or an event; this only bounds a broken run


@pytest.fixture
def context(monkeypatch: pytest.MonkeyPatch) -> Iterator[rclpy.Context]:
    monkeypatch.setenv("ROS2LAB_NO_ZENOH", "1")
    ctx = rclpy.Context()
    with rclpy.init(args=[], context=ctx):
        yield ctx


def adder(request: Any, response: Any) -> Any:
    response.sum = request.a + request.b
    return response


def test_init_is_a_context_manager_that_shuts_down_on_leaving_even_by_an_exception(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setenv("ROS2LAB_NO_ZENOH", "1")
    ctx = rclpy.Context()
    with pytest.raises(RuntimeError, match="boom"), rclpy.init(args=[], context=ctx):
        assert rclpy.ok(context=ctx)
        node = rclpy.create_node("inside", context=ctx)
        assert node.get_name() == "inside"
        raise RuntimeError("boom")
    assert not rclpy.ok(context=ctx)
    rclpy.init(args=[], context=ctx)  # a plain init still works, and needs its own shutdown
    assert rclpy.ok(context=ctx)
    rclpy.shutdown(context=ctx)


def test_future_runs_done_callbacks_once_and_at_once_when_already_done() -> None:
    future: Future[int] = Future()
    seen: list[int | None] = []
    future.add_done_callback(lambda f: seen.append(f.result()))
    assert not future.done() and seen == []
    future.set_result(7)
    future.set_result(8)  # a second result changes nothing
    future.add_done_callback(lambda f: seen.append(f.result()))
    assert seen == [7, 7]
    failed: Future[int] = Future()
    failed.set_exception(ValueError("no"))
    with pytest.raises(ValueError, match="no"):
        failed.result()


def test_single_threaded_spin_once_runs_ready_callbacks_and_returns_after_its_timeout(
    context: rclpy.Context,
) -> None:
    node = Node("counter", context=context)
    got: list[int] = []
    node.create_subscription(Int64, "n", lambda m: got.append(m.data), 10)
    pub = node.create_publisher(Int64, "n", 10)
    executor = SingleThreadedExecutor(context=context)
    executor.add_node(node)
    executor.spin_once(timeout_sec=0)  # nothing ready: returns
    for i in range(3):
        pub.publish(Int64(data=i))
    seen = []
    for _ in range(5):  # as rclpy's: one message a round; a round with timeout 0 ends in a timeout
        executor.spin_once(timeout_sec=0)
        seen.append(list(got))
    assert seen == [[0], [0], [0, 1], [0, 1], [0, 1, 2]]


def test_guard_condition_triggers_before_it_runs_collapse_into_one_run(context: rclpy.Context) -> None:
    node = Node("guarded", context=context)
    runs: list[int] = []
    guard = node.create_guard_condition(lambda: runs.append(1))
    executor = SingleThreadedExecutor(context=context)
    executor.add_node(node)
    guard.trigger()
    guard.trigger()
    executor.spin_once(timeout_sec=0)
    executor.spin_once(timeout_sec=0)
    assert runs == [1]
    guard.trigger()
    executor.spin_once(timeout_sec=0)
    assert runs == [1, 1]
    node.destroy_guard_condition(guard)
    guard.trigger()
    executor.spin_once(timeout_sec=0)
    assert runs == [1, 1]


class PriorityExecutor(Executor):
    """A custom executor as rclpy's examples build one: high-priority nodes' callbacks first."""

    def __init__(self, *, context: rclpy.Context) -> None:
        super().__init__(context=context)
        self.high: set[Node] = set()
        self.ran: list[str] = []

    def spin_once(self, timeout_sec: float | None = None) -> None:
        try:
            handler, _group, node = self.wait_for_ready_callbacks(timeout_sec=timeout_sec)
        except TimeoutException:
            return
        self.ran.append(node.get_name())
        handler()
        handler.result()


def test_a_custom_executor_gets_each_ready_callback_with_its_node(context: rclpy.Context) -> None:
    low, high = Node("low", context=context), Node("high", context=context)
    low_guard = low.create_guard_condition(lambda: None)
    high_guard = high.create_guard_condition(lambda: None)
    executor = PriorityExecutor(context=context)
    executor.add_node(low)
    executor.add_node(high)
    with pytest.raises(TimeoutException):
        executor.wait_for_ready_callbacks(timeout_sec=0)
    low_guard.trigger()
    high_guard.trigger()
    executor.spin_once(timeout_sec=0)
    executor.spin_once(timeout_sec=0)
    assert executor.ran == ["low", "high"]


def test_a_mutually_exclusive_group_runs_one_at_a_time_in_order_on_many_threads(
    context: rclpy.Context,
) -> None:
    node = Node("serial", context=context)
    group = MutuallyExclusiveCallbackGroup()
    order: list[int] = []
    active = [0, 0]  # now, most at once
    finished: Future[bool] = Future()

    def callback(msg: Int64) -> None:
        active[0] += 1
        active[1] = max(active)
        order.append(msg.data)
        active[0] -= 1
        if msg.data == 19:
            finished.set_result(True)

    node.create_subscription(Int64, "serial", callback, 100, callback_group=group)
    pub = node.create_publisher(Int64, "serial", 100)
    executor = MultiThreadedExecutor(num_threads=4, context=context)
    executor.add_node(node)
    for i in range(20):
        pub.publish(Int64(data=i))
    executor.spin_until_future_complete(finished, timeout_sec=BOUND_S)
    executor.shutdown()
    assert order == list(range(20)) and active[1] == 1


def test_a_reentrant_group_runs_its_callbacks_at_the_same_time(context: rclpy.Context) -> None:
    node = Node("parallel", context=context)
    group = ReentrantCallbackGroup()
    both = threading.Barrier(2, timeout=BOUND_S)  # passes only if the two run at once
    met: Future[int] = Future()
    passed: list[int] = []

    def meet(i: int) -> None:
        both.wait()
        passed.append(i)
        if len(passed) == 2:
            met.set_result(2)

    first = node.create_guard_condition(lambda: meet(1), callback_group=group)
    second = node.create_guard_condition(lambda: meet(2), callback_group=group)
    executor = MultiThreadedExecutor(num_threads=2, context=context)
    executor.add_node(node)
    first.trigger()
    second.trigger()
    executor.spin_until_future_complete(met, timeout_sec=BOUND_S)
    executor.shutdown()
    assert sorted(passed) == [1, 2]


def test_services_answer_on_a_multithreaded_executor_and_call_async_completes(context: rclpy.Context) -> None:
    node = Node("adder", context=context)
    node.create_service(AddTwoInts, "add", adder)
    client = node.create_client(AddTwoInts, "add")
    assert client.wait_for_service(timeout_sec=0)
    executor = MultiThreadedExecutor(context=context)
    executor.add_node(node)
    future = client.call_async(AddTwoInts.Request(a=2, b=40))
    executor.spin_until_future_complete(future, timeout_sec=BOUND_S)
    executor.shutdown()
    assert future.result().sum == 42


def test_client_call_from_another_thread_blocks_until_the_spinning_executor_answers(
    context: rclpy.Context,
) -> None:
    node = Node("sync", context=context)
    node.create_service(AddTwoInts, "add", adder)
    client = node.create_client(AddTwoInts, "add")
    answered: Future[Any] = Future()
    caller = threading.Thread(
        target=lambda: answered.set_result(client.call(AddTwoInts.Request(a=5, b=6), timeout_sec=BOUND_S))
    )
    caller.start()
    rclpy.spin_until_future_complete(
        node, answered, executor=SingleThreadedExecutor(context=context), timeout_sec=BOUND_S
    )
    caller.join(BOUND_S)
    assert answered.result().sum == 11


def test_wait_for_service_is_false_after_its_timeout_when_nobody_serves(context: rclpy.Context) -> None:
    node = Node("lonely", context=context)
    client = node.create_client(AddTwoInts, "nobody_serves_this")
    assert not client.wait_for_service(timeout_sec=0)
    with pytest.raises(TimeoutError):  # rclpy 9's call raises when its timeout passes
        client.call(AddTwoInts.Request(a=1, b=1), timeout_sec=0)
