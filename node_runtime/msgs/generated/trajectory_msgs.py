"""trajectory_msgs: generated from ROS 2's definitions (the wheels node_runtime/msgs/ros_packages.txt pins) by `python -m node_runtime.msgs.generate`; do not edit."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import numpy.typing as npt

from node_runtime.msgs._base import Message
from node_runtime.msgs._field import FloatArray
from node_runtime.msgs.generated.builtin_interfaces import Duration
from node_runtime.msgs.generated.geometry_msgs import Transform, Twist
from node_runtime.msgs.generated.std_msgs import Header


class JointTrajectoryPoint(Message, type_name="trajectory_msgs/msg/JointTrajectoryPoint"):
    """trajectory_msgs/msg/JointTrajectoryPoint: Each trajectory point specifies either positions[, velocities[, accelerations]]"""

    __slots__ = (
        "positions",
        "velocities",
        "accelerations",
        "effort",
        "time_from_start",
    )
    positions: FloatArray
    velocities: FloatArray
    accelerations: FloatArray
    effort: FloatArray
    time_from_start: Duration

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            positions: Sequence[float] | npt.NDArray[Any] = ...,
            velocities: Sequence[float] | npt.NDArray[Any] = ...,
            accelerations: Sequence[float] | npt.NDArray[Any] = ...,
            effort: Sequence[float] | npt.NDArray[Any] = ...,
            time_from_start: Duration = ...,
        ) -> None: ...


class JointTrajectory(Message, type_name="trajectory_msgs/msg/JointTrajectory"):
    """trajectory_msgs/msg/JointTrajectory: The header is used to specify the coordinate frame and the reference time for"""

    __slots__ = (
        "header",
        "joint_names",
        "points",
    )
    header: Header
    joint_names: list[str]
    points: list[JointTrajectoryPoint]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            joint_names: Sequence[str] = ...,
            points: Sequence[JointTrajectoryPoint] = ...,
        ) -> None: ...


class MultiDOFJointTrajectoryPoint(Message, type_name="trajectory_msgs/msg/MultiDOFJointTrajectoryPoint"):
    """trajectory_msgs/msg/MultiDOFJointTrajectoryPoint: Each multi-dof joint can specify a transform (up to 6 DOF)."""

    __slots__ = (
        "transforms",
        "velocities",
        "accelerations",
        "time_from_start",
    )
    transforms: list[Transform]
    velocities: list[Twist]
    accelerations: list[Twist]
    time_from_start: Duration

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            transforms: Sequence[Transform] = ...,
            velocities: Sequence[Twist] = ...,
            accelerations: Sequence[Twist] = ...,
            time_from_start: Duration = ...,
        ) -> None: ...


class MultiDOFJointTrajectory(Message, type_name="trajectory_msgs/msg/MultiDOFJointTrajectory"):
    """trajectory_msgs/msg/MultiDOFJointTrajectory: The header is used to specify the coordinate frame and the reference time for the trajectory durations"""

    __slots__ = (
        "header",
        "joint_names",
        "points",
    )
    header: Header
    joint_names: list[str]
    points: list[MultiDOFJointTrajectoryPoint]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            joint_names: Sequence[str] = ...,
            points: Sequence[MultiDOFJointTrajectoryPoint] = ...,
        ) -> None: ...


__all__ = [
    "JointTrajectory",
    "JointTrajectoryPoint",
    "MultiDOFJointTrajectory",
    "MultiDOFJointTrajectoryPoint",
]
