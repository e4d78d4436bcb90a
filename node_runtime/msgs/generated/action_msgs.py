"""action_msgs: generated from ROS 2's definitions (the wheels node_runtime/msgs/ros_packages.txt pins) by `python -m node_runtime.msgs.generate`; do not edit."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, ClassVar

from node_runtime.msgs._base import Message, Service
from node_runtime.msgs.generated.builtin_interfaces import Time
from node_runtime.msgs.generated.unique_identifier_msgs import UUID


class GoalInfo(Message, type_name="action_msgs/msg/GoalInfo"):
    """action_msgs/msg/GoalInfo: Goal ID"""

    __slots__ = (
        "goal_id",
        "stamp",
    )
    goal_id: UUID
    stamp: Time

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            goal_id: UUID = ...,
            stamp: Time = ...,
        ) -> None: ...


class GoalStatus(Message, type_name="action_msgs/msg/GoalStatus"):
    """action_msgs/msg/GoalStatus: An action goal can be in one of these states after it is accepted by an action"""

    __slots__ = (
        "goal_info",
        "status",
    )
    STATUS_UNKNOWN: ClassVar[int]
    STATUS_ACCEPTED: ClassVar[int]
    STATUS_EXECUTING: ClassVar[int]
    STATUS_CANCELING: ClassVar[int]
    STATUS_SUCCEEDED: ClassVar[int]
    STATUS_CANCELED: ClassVar[int]
    STATUS_ABORTED: ClassVar[int]
    goal_info: GoalInfo
    status: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            goal_info: GoalInfo = ...,
            status: int = ...,
        ) -> None: ...


class GoalStatusArray(Message, type_name="action_msgs/msg/GoalStatusArray"):
    """action_msgs/msg/GoalStatusArray: An array of goal statuses."""

    __slots__ = ("status_list",)
    status_list: list[GoalStatus]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            status_list: Sequence[GoalStatus] = ...,
        ) -> None: ...


class CancelGoal_Request(Message, type_name="action_msgs/srv/CancelGoal_Request"):
    """action_msgs/srv/CancelGoal_Request: Cancel one or more goals with the following policy:"""

    __slots__ = ("goal_info",)
    goal_info: GoalInfo

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            goal_info: GoalInfo = ...,
        ) -> None: ...


class CancelGoal_Response(Message, type_name="action_msgs/srv/CancelGoal_Response"):
    """action_msgs/srv/CancelGoal_Response"""

    __slots__ = (
        "return_code",
        "goals_canceling",
    )
    ERROR_NONE: ClassVar[int]
    ERROR_REJECTED: ClassVar[int]
    ERROR_UNKNOWN_GOAL_ID: ClassVar[int]
    ERROR_GOAL_TERMINATED: ClassVar[int]
    return_code: int
    goals_canceling: list[GoalInfo]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            return_code: int = ...,
            goals_canceling: Sequence[GoalInfo] = ...,
        ) -> None: ...


class CancelGoal(Service, type_name="action_msgs/srv/CancelGoal"):
    """action_msgs/srv/CancelGoal: call with a CancelGoal.Request, answered with a CancelGoal.Response."""

    Request = CancelGoal_Request
    Response = CancelGoal_Response


__all__ = [
    "CancelGoal",
    "CancelGoal_Request",
    "CancelGoal_Response",
    "GoalInfo",
    "GoalStatus",
    "GoalStatusArray",
]
