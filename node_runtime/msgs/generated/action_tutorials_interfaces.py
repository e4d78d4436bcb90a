"""action_tutorials_interfaces: generated from node_runtime/msgs/interfaces/action_tutorials_interfaces by `python -m node_runtime.msgs.generate`; do not edit."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import numpy.typing as npt

from node_runtime.msgs._action import Action
from node_runtime.msgs._base import Message, Service
from node_runtime.msgs._field import IntArray
from node_runtime.msgs.generated.action_msgs import CancelGoal, GoalStatusArray
from node_runtime.msgs.generated.builtin_interfaces import Time
from node_runtime.msgs.generated.unique_identifier_msgs import UUID


class Fibonacci_Goal(Message, type_name="action_tutorials_interfaces/action/Fibonacci_Goal"):
    """action_tutorials_interfaces/action/Fibonacci_Goal"""

    __slots__ = ("order",)
    order: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            order: int = ...,
        ) -> None: ...


class Fibonacci_Result(Message, type_name="action_tutorials_interfaces/action/Fibonacci_Result"):
    """action_tutorials_interfaces/action/Fibonacci_Result"""

    __slots__ = ("sequence",)
    sequence: IntArray

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            sequence: Sequence[int] | npt.NDArray[Any] = ...,
        ) -> None: ...


class Fibonacci_Feedback(Message, type_name="action_tutorials_interfaces/action/Fibonacci_Feedback"):
    """action_tutorials_interfaces/action/Fibonacci_Feedback"""

    __slots__ = ("partial_sequence",)
    partial_sequence: IntArray

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            partial_sequence: Sequence[int] | npt.NDArray[Any] = ...,
        ) -> None: ...


class Fibonacci_FeedbackMessage(
    Message, type_name="action_tutorials_interfaces/action/Fibonacci_FeedbackMessage"
):
    """action_tutorials_interfaces/action/Fibonacci_FeedbackMessage"""

    __slots__ = (
        "goal_id",
        "feedback",
    )
    goal_id: UUID
    feedback: Fibonacci_Feedback

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            goal_id: UUID = ...,
            feedback: Fibonacci_Feedback = ...,
        ) -> None: ...


class Fibonacci_SendGoal_Request(
    Message, type_name="action_tutorials_interfaces/action/Fibonacci_SendGoal_Request"
):
    """action_tutorials_interfaces/action/Fibonacci_SendGoal_Request"""

    __slots__ = (
        "goal_id",
        "goal",
    )
    goal_id: UUID
    goal: Fibonacci_Goal

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            goal_id: UUID = ...,
            goal: Fibonacci_Goal = ...,
        ) -> None: ...


class Fibonacci_SendGoal_Response(
    Message, type_name="action_tutorials_interfaces/action/Fibonacci_SendGoal_Response"
):
    """action_tutorials_interfaces/action/Fibonacci_SendGoal_Response"""

    __slots__ = (
        "accepted",
        "stamp",
    )
    accepted: bool
    stamp: Time

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            accepted: bool = ...,
            stamp: Time = ...,
        ) -> None: ...


class Fibonacci_GetResult_Request(
    Message, type_name="action_tutorials_interfaces/action/Fibonacci_GetResult_Request"
):
    """action_tutorials_interfaces/action/Fibonacci_GetResult_Request"""

    __slots__ = ("goal_id",)
    goal_id: UUID

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            goal_id: UUID = ...,
        ) -> None: ...


class Fibonacci_GetResult_Response(
    Message, type_name="action_tutorials_interfaces/action/Fibonacci_GetResult_Response"
):
    """action_tutorials_interfaces/action/Fibonacci_GetResult_Response"""

    __slots__ = (
        "status",
        "result",
    )
    status: int
    result: Fibonacci_Result

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            status: int = ...,
            result: Fibonacci_Result = ...,
        ) -> None: ...


class Fibonacci_SendGoal(Service, type_name="action_tutorials_interfaces/action/Fibonacci_SendGoal"):
    """action_tutorials_interfaces/action/Fibonacci_SendGoal: call with a Fibonacci_SendGoal.Request, answered with a Fibonacci_SendGoal.Response."""

    Request = Fibonacci_SendGoal_Request
    Response = Fibonacci_SendGoal_Response


class Fibonacci_GetResult(Service, type_name="action_tutorials_interfaces/action/Fibonacci_GetResult"):
    """action_tutorials_interfaces/action/Fibonacci_GetResult: call with a Fibonacci_GetResult.Request, answered with a Fibonacci_GetResult.Response."""

    Request = Fibonacci_GetResult_Request
    Response = Fibonacci_GetResult_Response


class Fibonacci(Action, type_name="action_tutorials_interfaces/action/Fibonacci"):
    """action_tutorials_interfaces/action/Fibonacci: a Fibonacci.Goal, answered with a Fibonacci.Result, Fibonacci.Feedback meanwhile."""

    Goal = Fibonacci_Goal
    Result = Fibonacci_Result
    Feedback = Fibonacci_Feedback

    class Impl:
        SendGoalService = Fibonacci_SendGoal
        GetResultService = Fibonacci_GetResult
        FeedbackMessage = Fibonacci_FeedbackMessage
        CancelGoalService = CancelGoal
        GoalStatusMessage = GoalStatusArray


__all__ = [
    "Fibonacci",
    "Fibonacci_Feedback",
    "Fibonacci_FeedbackMessage",
    "Fibonacci_GetResult",
    "Fibonacci_GetResult_Request",
    "Fibonacci_GetResult_Response",
    "Fibonacci_Goal",
    "Fibonacci_Result",
    "Fibonacci_SendGoal",
    "Fibonacci_SendGoal_Request",
    "Fibonacci_SendGoal_Response",
]
