"""turtlesim: generated from node_runtime/msgs/interfaces/turtlesim by `python -m node_runtime.msgs.generate`; do not edit."""

from __future__ import annotations

from typing import TYPE_CHECKING

from node_runtime.msgs._action import Action
from node_runtime.msgs._base import Message, Service
from node_runtime.msgs.generated.action_msgs import CancelGoal, GoalStatusArray
from node_runtime.msgs.generated.builtin_interfaces import Time
from node_runtime.msgs.generated.unique_identifier_msgs import UUID


class Color(Message, type_name="turtlesim/msg/Color"):
    """turtlesim/msg/Color: The color of the canvas under a turtle."""

    __slots__ = (
        "r",
        "g",
        "b",
    )
    r: int
    g: int
    b: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            r: int = ...,
            g: int = ...,
            b: int = ...,
        ) -> None: ...


class Pose(Message, type_name="turtlesim/msg/Pose"):
    """turtlesim/msg/Pose: A turtle's pose in turtlesim's window (meters, origin at the lower left) and its velocities."""

    __slots__ = (
        "x",
        "y",
        "theta",
        "linear_velocity",
        "angular_velocity",
    )
    x: float
    y: float
    theta: float
    linear_velocity: float
    angular_velocity: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            x: float = ...,
            y: float = ...,
            theta: float = ...,
            linear_velocity: float = ...,
            angular_velocity: float = ...,
        ) -> None: ...


class RotateAbsolute_Goal(Message, type_name="turtlesim/action/RotateAbsolute_Goal"):
    """turtlesim/action/RotateAbsolute_Goal: Turn the turtle in place to face theta (radians)."""

    __slots__ = ("theta",)
    theta: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            theta: float = ...,
        ) -> None: ...


class RotateAbsolute_Result(Message, type_name="turtlesim/action/RotateAbsolute_Result"):
    """turtlesim/action/RotateAbsolute_Result: How far it turned from where it faced at the start (radians)."""

    __slots__ = ("delta",)
    delta: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            delta: float = ...,
        ) -> None: ...


class RotateAbsolute_Feedback(Message, type_name="turtlesim/action/RotateAbsolute_Feedback"):
    """turtlesim/action/RotateAbsolute_Feedback: How far it still has to turn (radians)."""

    __slots__ = ("remaining",)
    remaining: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            remaining: float = ...,
        ) -> None: ...


class RotateAbsolute_FeedbackMessage(Message, type_name="turtlesim/action/RotateAbsolute_FeedbackMessage"):
    """turtlesim/action/RotateAbsolute_FeedbackMessage"""

    __slots__ = (
        "goal_id",
        "feedback",
    )
    goal_id: UUID
    feedback: RotateAbsolute_Feedback

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            goal_id: UUID = ...,
            feedback: RotateAbsolute_Feedback = ...,
        ) -> None: ...


class Kill_Request(Message, type_name="turtlesim/srv/Kill_Request"):
    """turtlesim/srv/Kill_Request: Remove the turtle of this name."""

    __slots__ = ("name",)
    name: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            name: str = ...,
        ) -> None: ...


class Kill_Response(Message, type_name="turtlesim/srv/Kill_Response"):
    """turtlesim/srv/Kill_Response"""

    __slots__ = ()


class SetPen_Request(Message, type_name="turtlesim/srv/SetPen_Request"):
    """turtlesim/srv/SetPen_Request: The turtle's pen: its color, its width in pixels (0 keeps 1), and off (non-zero lifts it)."""

    __slots__ = (
        "r",
        "g",
        "b",
        "width",
        "off",
    )
    r: int
    g: int
    b: int
    width: int
    off: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            r: int = ...,
            g: int = ...,
            b: int = ...,
            width: int = ...,
            off: int = ...,
        ) -> None: ...


class SetPen_Response(Message, type_name="turtlesim/srv/SetPen_Response"):
    """turtlesim/srv/SetPen_Response"""

    __slots__ = ()


class Spawn_Request(Message, type_name="turtlesim/srv/Spawn_Request"):
    """turtlesim/srv/Spawn_Request: A new turtle at (x, y) facing theta; with no name, turtlesim picks one and answers it."""

    __slots__ = (
        "x",
        "y",
        "theta",
        "name",
    )
    x: float
    y: float
    theta: float
    name: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            x: float = ...,
            y: float = ...,
            theta: float = ...,
            name: str = ...,
        ) -> None: ...


class Spawn_Response(Message, type_name="turtlesim/srv/Spawn_Response"):
    """turtlesim/srv/Spawn_Response"""

    __slots__ = ("name",)
    name: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            name: str = ...,
        ) -> None: ...


class TeleportAbsolute_Request(Message, type_name="turtlesim/srv/TeleportAbsolute_Request"):
    """turtlesim/srv/TeleportAbsolute_Request: Move the turtle to (x, y) facing theta."""

    __slots__ = (
        "x",
        "y",
        "theta",
    )
    x: float
    y: float
    theta: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            x: float = ...,
            y: float = ...,
            theta: float = ...,
        ) -> None: ...


class TeleportAbsolute_Response(Message, type_name="turtlesim/srv/TeleportAbsolute_Response"):
    """turtlesim/srv/TeleportAbsolute_Response"""

    __slots__ = ()


class TeleportRelative_Request(Message, type_name="turtlesim/srv/TeleportRelative_Request"):
    """turtlesim/srv/TeleportRelative_Request: Turn the turtle by angular, then move it linear meters ahead."""

    __slots__ = (
        "linear",
        "angular",
    )
    linear: float
    angular: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            linear: float = ...,
            angular: float = ...,
        ) -> None: ...


class TeleportRelative_Response(Message, type_name="turtlesim/srv/TeleportRelative_Response"):
    """turtlesim/srv/TeleportRelative_Response"""

    __slots__ = ()


class RotateAbsolute_SendGoal_Request(Message, type_name="turtlesim/action/RotateAbsolute_SendGoal_Request"):
    """turtlesim/action/RotateAbsolute_SendGoal_Request"""

    __slots__ = (
        "goal_id",
        "goal",
    )
    goal_id: UUID
    goal: RotateAbsolute_Goal

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            goal_id: UUID = ...,
            goal: RotateAbsolute_Goal = ...,
        ) -> None: ...


class RotateAbsolute_SendGoal_Response(
    Message, type_name="turtlesim/action/RotateAbsolute_SendGoal_Response"
):
    """turtlesim/action/RotateAbsolute_SendGoal_Response"""

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


class RotateAbsolute_GetResult_Request(
    Message, type_name="turtlesim/action/RotateAbsolute_GetResult_Request"
):
    """turtlesim/action/RotateAbsolute_GetResult_Request"""

    __slots__ = ("goal_id",)
    goal_id: UUID

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            goal_id: UUID = ...,
        ) -> None: ...


class RotateAbsolute_GetResult_Response(
    Message, type_name="turtlesim/action/RotateAbsolute_GetResult_Response"
):
    """turtlesim/action/RotateAbsolute_GetResult_Response"""

    __slots__ = (
        "status",
        "result",
    )
    status: int
    result: RotateAbsolute_Result

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            status: int = ...,
            result: RotateAbsolute_Result = ...,
        ) -> None: ...


class Kill(Service, type_name="turtlesim/srv/Kill"):
    """turtlesim/srv/Kill: call with a Kill.Request, answered with a Kill.Response."""

    Request = Kill_Request
    Response = Kill_Response


class SetPen(Service, type_name="turtlesim/srv/SetPen"):
    """turtlesim/srv/SetPen: call with a SetPen.Request, answered with a SetPen.Response."""

    Request = SetPen_Request
    Response = SetPen_Response


class Spawn(Service, type_name="turtlesim/srv/Spawn"):
    """turtlesim/srv/Spawn: call with a Spawn.Request, answered with a Spawn.Response."""

    Request = Spawn_Request
    Response = Spawn_Response


class TeleportAbsolute(Service, type_name="turtlesim/srv/TeleportAbsolute"):
    """turtlesim/srv/TeleportAbsolute: call with a TeleportAbsolute.Request, answered with a TeleportAbsolute.Response."""

    Request = TeleportAbsolute_Request
    Response = TeleportAbsolute_Response


class TeleportRelative(Service, type_name="turtlesim/srv/TeleportRelative"):
    """turtlesim/srv/TeleportRelative: call with a TeleportRelative.Request, answered with a TeleportRelative.Response."""

    Request = TeleportRelative_Request
    Response = TeleportRelative_Response


class RotateAbsolute_SendGoal(Service, type_name="turtlesim/action/RotateAbsolute_SendGoal"):
    """turtlesim/action/RotateAbsolute_SendGoal: call with a RotateAbsolute_SendGoal.Request, answered with a RotateAbsolute_SendGoal.Response."""

    Request = RotateAbsolute_SendGoal_Request
    Response = RotateAbsolute_SendGoal_Response


class RotateAbsolute_GetResult(Service, type_name="turtlesim/action/RotateAbsolute_GetResult"):
    """turtlesim/action/RotateAbsolute_GetResult: call with a RotateAbsolute_GetResult.Request, answered with a RotateAbsolute_GetResult.Response."""

    Request = RotateAbsolute_GetResult_Request
    Response = RotateAbsolute_GetResult_Response


class RotateAbsolute(Action, type_name="turtlesim/action/RotateAbsolute"):
    """turtlesim/action/RotateAbsolute: a RotateAbsolute.Goal, answered with a RotateAbsolute.Result, RotateAbsolute.Feedback meanwhile."""

    Goal = RotateAbsolute_Goal
    Result = RotateAbsolute_Result
    Feedback = RotateAbsolute_Feedback

    class Impl:
        SendGoalService = RotateAbsolute_SendGoal
        GetResultService = RotateAbsolute_GetResult
        FeedbackMessage = RotateAbsolute_FeedbackMessage
        CancelGoalService = CancelGoal
        GoalStatusMessage = GoalStatusArray


__all__ = [
    "Color",
    "Kill",
    "Kill_Request",
    "Kill_Response",
    "Pose",
    "RotateAbsolute",
    "RotateAbsolute_Feedback",
    "RotateAbsolute_FeedbackMessage",
    "RotateAbsolute_GetResult",
    "RotateAbsolute_GetResult_Request",
    "RotateAbsolute_GetResult_Response",
    "RotateAbsolute_Goal",
    "RotateAbsolute_Result",
    "RotateAbsolute_SendGoal",
    "RotateAbsolute_SendGoal_Request",
    "RotateAbsolute_SendGoal_Response",
    "SetPen",
    "SetPen_Request",
    "SetPen_Response",
    "Spawn",
    "Spawn_Request",
    "Spawn_Response",
    "TeleportAbsolute",
    "TeleportAbsolute_Request",
    "TeleportAbsolute_Response",
    "TeleportRelative",
    "TeleportRelative_Request",
    "TeleportRelative_Response",
]
