"""tf2_msgs: generated from node_runtime/msgs/interfaces/tf2_msgs by `python -m node_runtime.msgs.generate`; do not edit."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, ClassVar

from node_runtime.msgs._action import Action
from node_runtime.msgs._base import Message, Service
from node_runtime.msgs.generated.action_msgs import CancelGoal, GoalStatusArray
from node_runtime.msgs.generated.builtin_interfaces import Duration, Time
from node_runtime.msgs.generated.geometry_msgs import TransformStamped
from node_runtime.msgs.generated.unique_identifier_msgs import UUID


class TF2Error(Message, type_name="tf2_msgs/msg/TF2Error"):
    """tf2_msgs/msg/TF2Error: Why a transform could not be had (NO_ERROR when it could)."""

    __slots__ = (
        "error",
        "error_string",
    )
    NO_ERROR: ClassVar[int]
    LOOKUP_ERROR: ClassVar[int]
    CONNECTIVITY_ERROR: ClassVar[int]
    EXTRAPOLATION_ERROR: ClassVar[int]
    INVALID_ARGUMENT_ERROR: ClassVar[int]
    TIMEOUT_ERROR: ClassVar[int]
    TRANSFORM_ERROR: ClassVar[int]
    error: int
    error_string: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            error: int = ...,
            error_string: str = ...,
        ) -> None: ...


class TFMessage(Message, type_name="tf2_msgs/msg/TFMessage"):
    """tf2_msgs/msg/TFMessage: A batch of transforms, as /tf carries them."""

    __slots__ = ("transforms",)
    transforms: list[TransformStamped]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            transforms: Sequence[TransformStamped] = ...,
        ) -> None: ...


class LookupTransform_Goal(Message, type_name="tf2_msgs/action/LookupTransform_Goal"):
    """tf2_msgs/action/LookupTransform_Goal: Look a transform up: between two frames at one time, or (advanced) between two times through"""

    __slots__ = (
        "target_frame",
        "source_frame",
        "source_time",
        "timeout",
        "target_time",
        "fixed_frame",
        "advanced",
    )
    target_frame: str
    source_frame: str
    source_time: Time
    timeout: Duration
    target_time: Time
    fixed_frame: str
    advanced: bool

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            target_frame: str = ...,
            source_frame: str = ...,
            source_time: Time = ...,
            timeout: Duration = ...,
            target_time: Time = ...,
            fixed_frame: str = ...,
            advanced: bool = ...,
        ) -> None: ...


class LookupTransform_Result(Message, type_name="tf2_msgs/action/LookupTransform_Result"):
    """tf2_msgs/action/LookupTransform_Result"""

    __slots__ = (
        "transform",
        "error",
    )
    transform: TransformStamped
    error: TF2Error

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            transform: TransformStamped = ...,
            error: TF2Error = ...,
        ) -> None: ...


class LookupTransform_Feedback(Message, type_name="tf2_msgs/action/LookupTransform_Feedback"):
    """tf2_msgs/action/LookupTransform_Feedback"""

    __slots__ = ()


class LookupTransform_FeedbackMessage(Message, type_name="tf2_msgs/action/LookupTransform_FeedbackMessage"):
    """tf2_msgs/action/LookupTransform_FeedbackMessage"""

    __slots__ = (
        "goal_id",
        "feedback",
    )
    goal_id: UUID
    feedback: LookupTransform_Feedback

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            goal_id: UUID = ...,
            feedback: LookupTransform_Feedback = ...,
        ) -> None: ...


class FrameGraph_Request(Message, type_name="tf2_msgs/srv/FrameGraph_Request"):
    """tf2_msgs/srv/FrameGraph_Request: The frames a buffer knows, as YAML."""

    __slots__ = ()


class FrameGraph_Response(Message, type_name="tf2_msgs/srv/FrameGraph_Response"):
    """tf2_msgs/srv/FrameGraph_Response"""

    __slots__ = ("frame_yaml",)
    frame_yaml: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            frame_yaml: str = ...,
        ) -> None: ...


class LookupTransform_SendGoal_Request(Message, type_name="tf2_msgs/action/LookupTransform_SendGoal_Request"):
    """tf2_msgs/action/LookupTransform_SendGoal_Request"""

    __slots__ = (
        "goal_id",
        "goal",
    )
    goal_id: UUID
    goal: LookupTransform_Goal

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            goal_id: UUID = ...,
            goal: LookupTransform_Goal = ...,
        ) -> None: ...


class LookupTransform_SendGoal_Response(
    Message, type_name="tf2_msgs/action/LookupTransform_SendGoal_Response"
):
    """tf2_msgs/action/LookupTransform_SendGoal_Response"""

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


class LookupTransform_GetResult_Request(
    Message, type_name="tf2_msgs/action/LookupTransform_GetResult_Request"
):
    """tf2_msgs/action/LookupTransform_GetResult_Request"""

    __slots__ = ("goal_id",)
    goal_id: UUID

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            goal_id: UUID = ...,
        ) -> None: ...


class LookupTransform_GetResult_Response(
    Message, type_name="tf2_msgs/action/LookupTransform_GetResult_Response"
):
    """tf2_msgs/action/LookupTransform_GetResult_Response"""

    __slots__ = (
        "status",
        "result",
    )
    status: int
    result: LookupTransform_Result

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            status: int = ...,
            result: LookupTransform_Result = ...,
        ) -> None: ...


class FrameGraph(Service, type_name="tf2_msgs/srv/FrameGraph"):
    """tf2_msgs/srv/FrameGraph: call with a FrameGraph.Request, answered with a FrameGraph.Response."""

    Request = FrameGraph_Request
    Response = FrameGraph_Response


class LookupTransform_SendGoal(Service, type_name="tf2_msgs/action/LookupTransform_SendGoal"):
    """tf2_msgs/action/LookupTransform_SendGoal: call with a LookupTransform_SendGoal.Request, answered with a LookupTransform_SendGoal.Response."""

    Request = LookupTransform_SendGoal_Request
    Response = LookupTransform_SendGoal_Response


class LookupTransform_GetResult(Service, type_name="tf2_msgs/action/LookupTransform_GetResult"):
    """tf2_msgs/action/LookupTransform_GetResult: call with a LookupTransform_GetResult.Request, answered with a LookupTransform_GetResult.Response."""

    Request = LookupTransform_GetResult_Request
    Response = LookupTransform_GetResult_Response


class LookupTransform(Action, type_name="tf2_msgs/action/LookupTransform"):
    """tf2_msgs/action/LookupTransform: a LookupTransform.Goal, answered with a LookupTransform.Result, LookupTransform.Feedback meanwhile."""

    Goal = LookupTransform_Goal
    Result = LookupTransform_Result
    Feedback = LookupTransform_Feedback

    class Impl:
        SendGoalService = LookupTransform_SendGoal
        GetResultService = LookupTransform_GetResult
        FeedbackMessage = LookupTransform_FeedbackMessage
        CancelGoalService = CancelGoal
        GoalStatusMessage = GoalStatusArray


__all__ = [
    "FrameGraph",
    "FrameGraph_Request",
    "FrameGraph_Response",
    "LookupTransform",
    "LookupTransform_Feedback",
    "LookupTransform_FeedbackMessage",
    "LookupTransform_GetResult",
    "LookupTransform_GetResult_Request",
    "LookupTransform_GetResult_Response",
    "LookupTransform_Goal",
    "LookupTransform_Result",
    "LookupTransform_SendGoal",
    "LookupTransform_SendGoal_Request",
    "LookupTransform_SendGoal_Response",
    "TF2Error",
    "TFMessage",
]
