"""rclpy.action in one process without Zenoh: the goal state machine, the goal, cancel and
handle-accepted callbacks, results kept for late askers, the status topic and the cancel policy.
Waits end on a future; BOUND_S only bounds a broken run."""

from __future__ import annotations

import threading
from collections.abc import Iterator
from typing import Any

import pytest
import rclpy
from action_msgs.msg import GoalStatus, GoalStatusArray
from action_msgs.srv import CancelGoal
from action_tutorials_interfaces.action import Fibonacci
from rclpy.action import ActionClient, ActionServer, CancelResponse, GoalResponse, get_action_names_and_types
from rclpy.action.server import ServerGoalHandle
from rclpy.callback_groups import ReentrantCallbackGroup
from rclpy.executors import MultiThreadedExecutor, SingleThreadedExecutor
from rclpy.node import Node
from rclpy.task import Future
from unique_identifier_msgs.msg import UUID

BOUND_S = 10.0


@pytest.fixture
def node(monkeypatch: pytest.MonkeyPatch) -> Iterator[Node]:
    monkeypatch.setenv("ROS2LAB_NO_ZENOH", "1")
    ctx = rclpy.Context()
    with rclpy.init(args=[], context=ctx):
        node = Node("actions", context=ctx)
        EXECUTORS[node.get_name()] = SingleThreadedExecutor(context=ctx)
        yield node


EXECUTORS: dict[str, SingleThreadedExecutor] = {}


def spin_until(node: Node, future: Future[Any]) -> Any:
    rclpy.spin_until_future_complete(node, future, EXECUTORS[node.get_name()], timeout_sec=BOUND_S)
    assert future.done(), "the future did not complete"
    return future.result()


def fibonacci(handle: ServerGoalHandle) -> Any:
    seq = [0, 1]
    for i in range(1, handle.request.order):
        seq.append(seq[i] + seq[i - 1])
        handle.publish_feedback(Fibonacci.Feedback(partial_sequence=seq))
    handle.succeed()
    return Fibonacci.Result(sequence=seq)


def test_goal_runs_to_its_result_with_feedback_and_status_in_order(node: Node) -> None:
    ActionServer(node, Fibonacci, "fib", fibonacci)
    statuses: list[list[int]] = []
    node.create_subscription(
        GoalStatusArray,
        "fib/_action/status",
        lambda m: statuses.append([s.status for s in m.status_list]),
        10,
    )
    client = ActionClient(node, Fibonacci, "fib")
    assert client.wait_for_server(timeout_sec=BOUND_S)
    feedback: list[list[int]] = []
    handle = spin_until(
        node,
        client.send_goal_async(
            Fibonacci.Goal(order=4),
            feedback_callback=lambda m: feedback.append(list(m.feedback.partial_sequence)),
        ),
    )
    assert handle.accepted
    answer = spin_until(node, handle.get_result_async())
    assert (answer.status, list(answer.result.sequence)) == (GoalStatus.STATUS_SUCCEEDED, [0, 1, 1, 2, 3])
    marker = spin_until(node, client.send_goal_async(Fibonacci.Goal(order=1)))  # later than all of the above
    spin_until(node, marker.get_result_async())
    EXECUTORS[node.get_name()].spin_once(timeout_sec=0)
    assert feedback == [[0, 1, 1], [0, 1, 1, 2], [0, 1, 1, 2, 3]]
    assert statuses[:3] == [[1], [2], [4]]  # accepted, executing, succeeded
    assert handle.status == GoalStatus.STATUS_SUCCEEDED


def test_goal_callback_rejects_and_the_handle_says_not_accepted(node: Node) -> None:
    ran: list[int] = []

    def execute(handle: ServerGoalHandle) -> Any:
        ran.append(handle.request.order)
        return fibonacci(handle)

    ActionServer(
        node,
        Fibonacci,
        "fib",
        execute,
        goal_callback=lambda g: GoalResponse.REJECT if g.order > 46 else GoalResponse.ACCEPT,
    )
    client = ActionClient(node, Fibonacci, "fib")
    refused = spin_until(node, client.send_goal_async(Fibonacci.Goal(order=47)))
    assert not refused.accepted
    with pytest.raises(TypeError, match="not accepted"):
        refused.get_result_async()
    accepted = spin_until(node, client.send_goal_async(Fibonacci.Goal(order=2)))
    spin_until(node, accepted.get_result_async())
    assert ran == [2]  # the rejected goal never ran


def test_execute_callback_that_sets_no_state_aborts_with_a_warning(node: Node, capsys: Any) -> None:
    ActionServer(node, Fibonacci, "fib", lambda handle: Fibonacci.Result(sequence=[7]))
    client = ActionClient(node, Fibonacci, "fib")
    handle = spin_until(node, client.send_goal_async(Fibonacci.Goal(order=3)))
    answer = spin_until(node, handle.get_result_async())
    assert (answer.status, list(answer.result.sequence)) == (GoalStatus.STATUS_ABORTED, [7])
    assert "Goal state not set, assuming aborted. Goal ID: [" in capsys.readouterr().err


def test_result_asked_after_the_goal_finished_is_kept_and_an_unknown_goal_is_unknown(node: Node) -> None:
    ActionServer(node, Fibonacci, "fib", fibonacci)
    client = ActionClient(node, Fibonacci, "fib")
    handle = spin_until(node, client.send_goal_async(Fibonacci.Goal(order=3)))
    first = spin_until(node, handle.get_result_async())
    again = spin_until(node, handle.get_result_async())
    assert list(again.result.sequence) == list(first.result.sequence) == [0, 1, 1, 2]
    getter = node.create_client(Fibonacci.Impl.GetResultService, "fib/_action/get_result")
    unknown = spin_until(
        node, getter.call_async(Fibonacci.Impl.GetResultService.Request(goal_id=UUID(uuid=[9] * 16)))
    )
    assert unknown.status == GoalStatus.STATUS_UNKNOWN


def test_invalid_transition_raises_and_changes_nothing(node: Node) -> None:
    seen: list[str] = []

    def execute(handle: ServerGoalHandle) -> Any:
        handle.succeed()
        try:
            handle.abort()  # a finished goal cannot be aborted
        except rclpy.RCLError as exc:
            seen.append(str(exc))
        return Fibonacci.Result()

    ActionServer(node, Fibonacci, "fib", execute)
    client = ActionClient(node, Fibonacci, "fib")
    handle = spin_until(node, client.send_goal_async(Fibonacci.Goal(order=1)))
    assert spin_until(node, handle.get_result_async()).status == GoalStatus.STATUS_SUCCEEDED
    assert seen and "invalid transition from state SUCCEEDED with event ABORT" in seen[0]


def test_cancel_accepted_while_executing_on_a_multithreaded_executor(node: Node) -> None:
    started, stop = threading.Event(), threading.Event()

    def execute(handle: ServerGoalHandle) -> Any:
        started.set()
        while not handle.is_cancel_requested:
            stop.wait(0.01)
        handle.canceled()
        return Fibonacci.Result(sequence=[1])

    group = ReentrantCallbackGroup()
    ActionServer(
        node,
        Fibonacci,
        "fib",
        execute,
        callback_group=group,
        cancel_callback=lambda handle: CancelResponse.ACCEPT,
    )
    client = ActionClient(node, Fibonacci, "fib", callback_group=group)
    executor = MultiThreadedExecutor(num_threads=3, context=node._rcl_context)
    executor.add_node(node)
    spinner = threading.Thread(target=executor.spin, daemon=True)
    spinner.start()
    handle = waited(client.send_goal_async(Fibonacci.Goal(order=5)))
    assert started.wait(BOUND_S)
    cancel = waited(handle.cancel_goal_async())
    assert cancel.return_code == CancelGoal.Response.ERROR_NONE
    assert [bytes(g.goal_id.uuid) for g in cancel.goals_canceling] == [bytes(handle.goal_id.uuid)]
    answer = waited(handle.get_result_async())
    assert (answer.status, list(answer.result.sequence)) == (GoalStatus.STATUS_CANCELED, [1])
    executor.shutdown()
    spinner.join(BOUND_S)


def waited(future: Future[Any]) -> Any:
    """The result of a future an executor spinning in another thread completes."""
    assert future.wait(BOUND_S), "the future did not complete"
    return future.result()


def test_cancel_policy_refusals_name_why(node: Node) -> None:
    ActionServer(node, Fibonacci, "fib", fibonacci)  # the default cancel callback refuses
    client = ActionClient(node, Fibonacci, "fib")
    canceller = node.create_client(CancelGoal, "fib/_action/cancel_goal")
    handle = spin_until(node, client.send_goal_async(Fibonacci.Goal(order=2)))
    spin_until(node, handle.get_result_async())
    finished = spin_until(node, handle.cancel_goal_async())
    assert (finished.return_code, list(finished.goals_canceling)) == (
        CancelGoal.Response.ERROR_GOAL_TERMINATED,
        [],
    )
    unknown = CancelGoal.Request()
    unknown.goal_info.goal_id.uuid = [5] * 16
    answer = spin_until(node, canceller.call_async(unknown))
    assert answer.return_code == CancelGoal.Response.ERROR_UNKNOWN_GOAL_ID


def test_feedback_of_the_wrong_type_is_a_type_error_and_actions_are_in_the_graph(node: Node) -> None:
    errors: list[str] = []

    def execute(handle: ServerGoalHandle) -> Any:
        try:
            handle.publish_feedback(Fibonacci.Result())
        except TypeError as exc:
            errors.append(str(exc))
        handle.succeed()
        return Fibonacci.Result()

    ActionServer(node, Fibonacci, "fib", execute)
    client = ActionClient(node, Fibonacci, "fib")
    with pytest.raises(TypeError, match="goal must be a"):
        client.send_goal_async(Fibonacci.Result())
    spin_until(node, spin_until(node, client.send_goal_async(Fibonacci.Goal())).get_result_async())
    assert errors == [
        "feedback must be a action_tutorials_interfaces/action/Fibonacci_Feedback, not Fibonacci_Result"
    ]
    assert get_action_names_and_types(node) == [("/fib", ["action_tutorials_interfaces/action/Fibonacci"])]
