"""The executor model as rclpy 9 has it, in one process without Zenoh: async callbacks and tasks
that await futures, wait_for_ready_callbacks' waits and exceptions, a callback group's three
questions, and a node no executor spins. Waits end on a future or an event; BOUND_S only bounds
a broken run."""

from __future__ import annotations

import threading
from collections.abc import Iterator
from typing import Any

import pytest
import rclpy
from action_tutorials_interfaces.action import Fibonacci
from example_interfaces.srv import AddTwoInts
from rclpy.action import ActionClient, ActionServer
from rclpy.callback_groups import CallbackGroup, ReentrantCallbackGroup
from rclpy.executors import (
    Executor,
    ExternalShutdownException,
    MultiThreadedExecutor,
    ShutdownException,
    SingleThreadedExecutor,
    TimeoutException,
)
from rclpy.node import Node
from rclpy.task import Future, Task
from std_msgs.msg import Int64

BOUND_S = 10.0


@pytest.fixture
def context(monkeypatch: pytest.MonkeyPatch) -> Iterator[rclpy.Context]:
    monkeypatch.setenv("ROS2LAB_NO_ZENOH", "1")
    ctx = rclpy.Context()
    with rclpy.init(args=[], context=ctx):
        yield ctx


async def async_adder(request: Any, response: Any) -> Any:
    response.sum = request.a + request.b
    return response


@pytest.mark.parametrize("executor_type", [SingleThreadedExecutor, MultiThreadedExecutor])
def test_a_task_awaits_an_async_service_through_a_client_and_spinning_until_it_gives_its_result(
    context: rclpy.Context, executor_type: type[Executor]
) -> None:
    server, caller = Node("adder", context=context), Node("caller", context=context)
    server.create_service(AddTwoInts, "add", async_adder)
    client = caller.create_client(AddTwoInts, "add")
    executor = executor_type(context=context)
    executor.add_node(server)
    executor.add_node(caller)

    async def ask(a: int, b: int) -> int:
        first = await client.call_async(AddTwoInts.Request(a=a, b=b))
        second = await client.call_async(AddTwoInts.Request(a=first.sum, b=b))
        return int(second.sum)

    task = executor.create_task(ask, 2, 3)
    assert isinstance(task, Task) and not task.done()
    executor.spin_until_future_complete(task, timeout_sec=BOUND_S)
    executor.shutdown()
    assert task.result() == 8


def test_an_async_timer_awaiting_a_client_of_its_own_mutually_exclusive_group_never_gets_the_answer(
    context: rclpy.Context,
) -> None:
    """As in rclpy: the response waits for the group the awaiting callback holds. With the
    client in a reentrant group the same callback gets it."""
    server, caller = Node("adder", context=context), Node("caller", context=context)
    server.create_service(AddTwoInts, "add", async_adder)
    stuck_client = caller.create_client(AddTwoInts, "add")
    free_client = caller.create_client(AddTwoInts, "add", callback_group=ReentrantCallbackGroup())
    answers: dict[str, int] = {}
    done: Future[bool] = Future()

    async def ask_both() -> None:
        free = await free_client.call_async(AddTwoInts.Request(a=1, b=1))
        answers["free"] = free.sum
        done.set_result(True)
        stuck = await stuck_client.call_async(AddTwoInts.Request(a=2, b=2))
        answers["stuck"] = stuck.sum

    timer = caller.create_timer(0.001, ask_both)
    executor = SingleThreadedExecutor(context=context)
    executor.add_node(server)
    executor.add_node(caller)
    executor.spin_until_future_complete(done, timeout_sec=BOUND_S)
    timer.cancel()
    for _ in range(20):  # every round there is: the stuck answer is there, held back by the group
        executor.spin_once(timeout_sec=0)
    assert answers == {"free": 2}


def test_wait_for_ready_callbacks_waits_without_a_timeout_and_raises_as_rclpy_does(
    context: rclpy.Context,
) -> None:
    node = Node("waiter", context=context)
    ran: list[str] = []
    guard = node.create_guard_condition(lambda: ran.append("guard"))
    executor = Executor(context=context)
    executor.add_node(node)
    with pytest.raises(NotImplementedError):
        executor.spin_once(timeout_sec=0)
    with pytest.raises(TimeoutException):
        executor.wait_for_ready_callbacks(timeout_sec=0)
    waiting = threading.Event()
    trigger = threading.Thread(target=lambda: (waiting.wait(BOUND_S), guard.trigger()))
    trigger.start()
    waiting.set()
    handler, entity, owner = executor.wait_for_ready_callbacks()  # no timeout: waits for the guard
    trigger.join(BOUND_S)
    handler()
    assert (ran, entity, owner) == (["guard"], guard, node)
    executor.shutdown()
    with pytest.raises(ShutdownException):
        executor.wait_for_ready_callbacks(timeout_sec=0)


def test_a_context_shut_down_from_another_thread_ends_a_single_threaded_spin_with_an_exception(
    context: rclpy.Context,
) -> None:
    node = Node("spinner", context=context)
    executor = SingleThreadedExecutor(context=context)
    executor.add_node(node)
    spinning = Future[bool]()
    node.create_guard_condition(lambda: spinning.set_result(True)).trigger()
    stopper = threading.Thread(target=lambda: (spinning.wait(BOUND_S), rclpy.shutdown(context=context)))
    stopper.start()
    with pytest.raises(ExternalShutdownException):
        executor.spin()
    stopper.join(BOUND_S)
    assert spinning.done() and not context.ok()
    rclpy.init(args=[], context=context)  # for the fixture's own shutdown


class Gate(CallbackGroup):
    """A custom group: shut, nothing may run; open, each callback is told about on both ends."""

    def __init__(self) -> None:
        super().__init__()
        self.open = False
        self.refuse_next = False
        self.log: list[str] = []

    def can_execute(self, entity: Any) -> bool:
        return self.open

    def beginning_execution(self, entity: Any) -> bool:
        if self.refuse_next:  # changed its mind between the executor's question and the start
            self.refuse_next = False
            self.log.append("refused")
            return False
        self.log.append("begin")
        return True

    def ending_execution(self, entity: Any) -> None:
        self.log.append("end")


def test_a_custom_group_is_asked_before_and_told_after_and_a_refused_callback_stays_ready(
    context: rclpy.Context,
) -> None:
    node = Node("gated", context=context)
    gate = Gate()
    got: list[int] = []
    sub = node.create_subscription(
        Int64, "n", lambda m: (got.append(m.data), gate.log.append("ran")), 10, callback_group=gate
    )
    pub = node.create_publisher(Int64, "n", 10)
    executor = SingleThreadedExecutor(context=context)
    executor.add_node(node)
    pub.publish(Int64(data=1))
    pub.publish(Int64(data=2))
    for _ in range(4):
        executor.spin_once(timeout_sec=0)
    assert (got, gate.log) == ([], [])  # shut: nothing ran, nothing was begun
    gate.open, gate.refuse_next = True, True
    handler, entity, _node = executor.wait_for_ready_callbacks(timeout_sec=0)
    handler()
    assert (entity, got, gate.log) == (sub, [], ["refused"])  # refused: the message stays
    for _ in range(6):
        executor.spin_once(timeout_sec=0)
    assert got == [1, 2]
    assert gate.log == ["refused", "begin", "ran", "end", "begin", "ran", "end"]


def test_a_node_no_executor_has_runs_nothing_until_one_spins_it(context: rclpy.Context) -> None:
    spun, idle = Node("spun", context=context), Node("idle", context=context)
    heard: list[str] = []
    idle.create_subscription(Int64, "n", lambda m: heard.append("idle"), 10)
    spun.create_subscription(Int64, "n", lambda m: heard.append("spun"), 10)
    pub = spun.create_publisher(Int64, "n", 10)
    executor = SingleThreadedExecutor(context=context)
    executor.add_node(spun)
    pub.publish(Int64(data=1))
    for _ in range(4):
        executor.spin_once(timeout_sec=0)
    assert heard == ["spun"]
    assert spun.executor is executor and idle.executor is None
    other = SingleThreadedExecutor(context=context)
    idle.executor = other  # rclpy's setter adds it
    assert other.get_nodes() == [idle]
    other.spin_once(timeout_sec=0)
    assert heard == ["spun", "idle"]


def test_an_async_execute_callback_awaits_while_the_single_thread_serves_feedback_and_a_client_task(
    context: rclpy.Context,
) -> None:
    node = Node("fibonacci", context=context)
    steps: list[Future[bool]] = [Future() for _ in range(3)]
    released: list[int] = []

    async def execute(handle: Any) -> Any:
        seq = [0, 1]
        for step in steps:
            await step  # the executor runs everything else meanwhile, the client's task included
            seq.append(seq[-1] + seq[-2])
            handle.publish_feedback(Fibonacci.Feedback(partial_sequence=seq))
        handle.succeed()
        return Fibonacci.Result(sequence=seq)

    def release(feedback: Any) -> None:
        released.append(len(feedback.feedback.partial_sequence))
        if len(released) < len(steps):
            steps[len(released)].set_result(True)

    ActionServer(node, Fibonacci, "fib", execute)
    client = ActionClient(node, Fibonacci, "fib")
    executor = SingleThreadedExecutor(context=context)
    executor.add_node(node)

    async def run_goal() -> list[int]:
        handle = await client.send_goal_async(Fibonacci.Goal(order=5), feedback_callback=release)
        steps[0].set_result(True)
        response = await handle.get_result_async()
        return list(response.result.sequence)

    task = executor.create_task(run_goal)
    executor.spin_until_future_complete(task, timeout_sec=BOUND_S)
    assert task.result() == [0, 1, 1, 2, 3]
    assert released == [3, 4, 5]


def test_after_a_callback_the_next_wait_blocks_rather_than_turning_once_idle(
    context: rclpy.Context, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A callback's end wakes the wait set (its group may let another in). The thread that ran it
    looks again anyway, so that wake must not make its next wait on the bus return at once: an
    idle turn per callback doubled a 10 Hz node's CPU. Each wait here blocks until the guard is
    triggered from another thread, and each trigger runs its callback once."""
    node = Node("ticker", context=context)
    ran: list[int] = []
    guard = node.create_guard_condition(lambda: ran.append(len(ran)))
    executor = SingleThreadedExecutor(context=context)
    executor.add_node(node)
    wait_set = context.executor
    blocked = threading.Event()
    waits: list[float] = []
    blocks: list[float | None] = []
    real_wait, real_block = wait_set._wait, wait_set._cv.wait

    def counted_wait(until_s: float) -> None:
        waits.append(until_s)
        real_wait(until_s)

    def counted_block(timeout: float | None = None) -> bool:
        blocks.append(timeout)
        blocked.set()
        return real_block(timeout)

    monkeypatch.setattr(wait_set, "_wait", counted_wait)
    monkeypatch.setattr(wait_set._cv, "wait", counted_block)
    triggers = 5

    def trigger() -> None:
        for _ in range(triggers):
            assert blocked.wait(BOUND_S)
            blocked.clear()
            guard.trigger()

    thread = threading.Thread(target=trigger)
    thread.start()
    for _ in range(triggers):
        executor.spin_once(timeout_sec=BOUND_S)
    thread.join(BOUND_S)
    assert ran == list(range(triggers))
    assert len(waits) == len(blocks) == triggers  # every wait blocked; none was an idle turn
