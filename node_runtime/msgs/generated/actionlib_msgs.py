"""actionlib_msgs: generated from ROS 2's definitions (the wheels node_runtime/msgs/ros_packages.txt pins) by `python -m node_runtime.msgs.generate`; do not edit."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, ClassVar

from node_runtime.msgs._base import Message
from node_runtime.msgs.generated.builtin_interfaces import Time
from node_runtime.msgs.generated.std_msgs import Header


class GoalID(Message, type_name="actionlib_msgs/msg/GoalID"):
    """actionlib_msgs/msg/GoalID: The stamp should store the time at which this goal was requested."""

    __slots__ = (
        "stamp",
        "id",
    )
    stamp: Time
    id: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            stamp: Time = ...,
            id: str = ...,
        ) -> None: ...


class GoalStatus(Message, type_name="actionlib_msgs/msg/GoalStatus"):
    """actionlib_msgs/msg/GoalStatus: Allow for the user to associate a string with GoalStatus for debugging."""

    __slots__ = (
        "goal_id",
        "status",
        "text",
    )
    PENDING: ClassVar[int]
    ACTIVE: ClassVar[int]
    PREEMPTED: ClassVar[int]
    SUCCEEDED: ClassVar[int]
    ABORTED: ClassVar[int]
    REJECTED: ClassVar[int]
    PREEMPTING: ClassVar[int]
    RECALLING: ClassVar[int]
    RECALLED: ClassVar[int]
    LOST: ClassVar[int]
    goal_id: GoalID
    status: int
    text: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            goal_id: GoalID = ...,
            status: int = ...,
            text: str = ...,
        ) -> None: ...


class GoalStatusArray(Message, type_name="actionlib_msgs/msg/GoalStatusArray"):
    """actionlib_msgs/msg/GoalStatusArray: Stores the statuses for goals that are currently being tracked"""

    __slots__ = (
        "header",
        "status_list",
    )
    header: Header
    status_list: list[GoalStatus]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            status_list: Sequence[GoalStatus] = ...,
        ) -> None: ...


__all__ = [
    "GoalID",
    "GoalStatus",
    "GoalStatusArray",
]
