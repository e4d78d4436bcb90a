"""nav_msgs: generated from ROS 2's definitions (the wheels node_runtime/msgs/ros_packages.txt pins) by `python -m node_runtime.msgs.generate`; do not edit."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any, ClassVar

if TYPE_CHECKING:
    import numpy.typing as npt

from node_runtime.msgs._base import Message, Service
from node_runtime.msgs._field import IntArray
from node_runtime.msgs.generated.builtin_interfaces import Time
from node_runtime.msgs.generated.geometry_msgs import (
    Point,
    Pose,
    PoseStamped,
    PoseWithCovariance,
    PoseWithCovarianceStamped,
    TwistWithCovariance,
)
from node_runtime.msgs.generated.std_msgs import Header


class Goals(Message, type_name="nav_msgs/msg/Goals"):
    """nav_msgs/msg/Goals: An array of navigation goals"""

    __slots__ = (
        "header",
        "goals",
    )
    header: Header
    goals: list[PoseStamped]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            goals: Sequence[PoseStamped] = ...,
        ) -> None: ...


class GridCells(Message, type_name="nav_msgs/msg/GridCells"):
    """nav_msgs/msg/GridCells: An array of cells in a 2D grid"""

    __slots__ = (
        "header",
        "cell_width",
        "cell_height",
        "cells",
    )
    header: Header
    cell_width: float
    cell_height: float
    cells: list[Point]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            cell_width: float = ...,
            cell_height: float = ...,
            cells: Sequence[Point] = ...,
        ) -> None: ...


class MapMetaData(Message, type_name="nav_msgs/msg/MapMetaData"):
    """nav_msgs/msg/MapMetaData: This hold basic information about the characteristics of the OccupancyGrid"""

    __slots__ = (
        "map_load_time",
        "resolution",
        "width",
        "height",
        "origin",
    )
    map_load_time: Time
    resolution: float
    width: int
    height: int
    origin: Pose

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            map_load_time: Time = ...,
            resolution: float = ...,
            width: int = ...,
            height: int = ...,
            origin: Pose = ...,
        ) -> None: ...


class OccupancyGrid(Message, type_name="nav_msgs/msg/OccupancyGrid"):
    """nav_msgs/msg/OccupancyGrid: This represents a 2-D grid map"""

    __slots__ = (
        "header",
        "info",
        "data",
    )
    header: Header
    info: MapMetaData
    data: IntArray

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            info: MapMetaData = ...,
            data: Sequence[int] | npt.NDArray[Any] = ...,
        ) -> None: ...


class Odometry(Message, type_name="nav_msgs/msg/Odometry"):
    """nav_msgs/msg/Odometry: This represents an estimate of a position and velocity in free space."""

    __slots__ = (
        "header",
        "child_frame_id",
        "pose",
        "twist",
    )
    header: Header
    child_frame_id: str
    pose: PoseWithCovariance
    twist: TwistWithCovariance

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            child_frame_id: str = ...,
            pose: PoseWithCovariance = ...,
            twist: TwistWithCovariance = ...,
        ) -> None: ...


class Path(Message, type_name="nav_msgs/msg/Path"):
    """nav_msgs/msg/Path: An array of poses that represents a Path for a robot to follow."""

    __slots__ = (
        "header",
        "poses",
    )
    header: Header
    poses: list[PoseStamped]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            poses: Sequence[PoseStamped] = ...,
        ) -> None: ...


class GetMap_Request(Message, type_name="nav_msgs/srv/GetMap_Request"):
    """nav_msgs/srv/GetMap_Request: Get the map as a nav_msgs/OccupancyGrid"""

    __slots__ = ()


class GetMap_Response(Message, type_name="nav_msgs/srv/GetMap_Response"):
    """nav_msgs/srv/GetMap_Response: The current map hosted by this map service."""

    __slots__ = ("map",)
    map: OccupancyGrid

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            map: OccupancyGrid = ...,
        ) -> None: ...


class GetPlan_Request(Message, type_name="nav_msgs/srv/GetPlan_Request"):
    """nav_msgs/srv/GetPlan_Request: Get a plan from the current position to the goal Pose"""

    __slots__ = (
        "start",
        "goal",
        "tolerance",
    )
    start: PoseStamped
    goal: PoseStamped
    tolerance: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            start: PoseStamped = ...,
            goal: PoseStamped = ...,
            tolerance: float = ...,
        ) -> None: ...


class GetPlan_Response(Message, type_name="nav_msgs/srv/GetPlan_Response"):
    """nav_msgs/srv/GetPlan_Response: Array of poses from start to goal if one was successfully found."""

    __slots__ = ("plan",)
    plan: Path

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            plan: Path = ...,
        ) -> None: ...


class LoadMap_Request(Message, type_name="nav_msgs/srv/LoadMap_Request"):
    """nav_msgs/srv/LoadMap_Request: URL of map resource"""

    __slots__ = ("map_url",)
    map_url: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            map_url: str = ...,
        ) -> None: ...


class LoadMap_Response(Message, type_name="nav_msgs/srv/LoadMap_Response"):
    """nav_msgs/srv/LoadMap_Response: Result code definitions"""

    __slots__ = (
        "map",
        "result",
    )
    RESULT_SUCCESS: ClassVar[int]
    RESULT_MAP_DOES_NOT_EXIST: ClassVar[int]
    RESULT_INVALID_MAP_DATA: ClassVar[int]
    RESULT_INVALID_MAP_METADATA: ClassVar[int]
    RESULT_UNDEFINED_FAILURE: ClassVar[int]
    map: OccupancyGrid
    result: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            map: OccupancyGrid = ...,
            result: int = ...,
        ) -> None: ...


class SetMap_Request(Message, type_name="nav_msgs/srv/SetMap_Request"):
    """nav_msgs/srv/SetMap_Request: Set a new map together with an initial pose"""

    __slots__ = (
        "map",
        "initial_pose",
    )
    map: OccupancyGrid
    initial_pose: PoseWithCovarianceStamped

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            map: OccupancyGrid = ...,
            initial_pose: PoseWithCovarianceStamped = ...,
        ) -> None: ...


class SetMap_Response(Message, type_name="nav_msgs/srv/SetMap_Response"):
    """nav_msgs/srv/SetMap_Response: True if the map was successfully set, false otherwise."""

    __slots__ = ("success",)
    success: bool

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            success: bool = ...,
        ) -> None: ...


class GetMap(Service, type_name="nav_msgs/srv/GetMap"):
    """nav_msgs/srv/GetMap: call with a GetMap.Request, answered with a GetMap.Response."""

    Request = GetMap_Request
    Response = GetMap_Response


class GetPlan(Service, type_name="nav_msgs/srv/GetPlan"):
    """nav_msgs/srv/GetPlan: call with a GetPlan.Request, answered with a GetPlan.Response."""

    Request = GetPlan_Request
    Response = GetPlan_Response


class LoadMap(Service, type_name="nav_msgs/srv/LoadMap"):
    """nav_msgs/srv/LoadMap: call with a LoadMap.Request, answered with a LoadMap.Response."""

    Request = LoadMap_Request
    Response = LoadMap_Response


class SetMap(Service, type_name="nav_msgs/srv/SetMap"):
    """nav_msgs/srv/SetMap: call with a SetMap.Request, answered with a SetMap.Response."""

    Request = SetMap_Request
    Response = SetMap_Response


__all__ = [
    "GetMap",
    "GetMap_Request",
    "GetMap_Response",
    "GetPlan",
    "GetPlan_Request",
    "GetPlan_Response",
    "Goals",
    "GridCells",
    "LoadMap",
    "LoadMap_Request",
    "LoadMap_Response",
    "MapMetaData",
    "OccupancyGrid",
    "Odometry",
    "Path",
    "SetMap",
    "SetMap_Request",
    "SetMap_Response",
]
