"""geometry_msgs: generated from server/msgs/interfaces/geometry_msgs by `python -m server.msgs.generate`; do not edit."""

from __future__ import annotations

from typing import TYPE_CHECKING

from .._base import Message
from .std_msgs import Header


class Point(Message, type_name="geometry_msgs/msg/Point"):
    """geometry_msgs/msg/Point: A position in free space (metres)."""

    __slots__ = (
        "x",
        "y",
        "z",
    )
    x: float
    y: float
    z: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            x: float = ...,
            y: float = ...,
            z: float = ...,
        ) -> None: ...


class PointStamped(Message, type_name="geometry_msgs/msg/PointStamped"):
    """geometry_msgs/msg/PointStamped: A point with a time and a frame."""

    __slots__ = (
        "header",
        "point",
    )
    header: Header
    point: Point

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            point: Point = ...,
        ) -> None: ...


class Quaternion(Message, type_name="geometry_msgs/msg/Quaternion"):
    """geometry_msgs/msg/Quaternion: An orientation as a unit quaternion; the default is the identity."""

    __slots__ = (
        "x",
        "y",
        "z",
        "w",
    )
    x: float
    y: float
    z: float
    w: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            x: float = ...,
            y: float = ...,
            z: float = ...,
            w: float = ...,
        ) -> None: ...


class Pose(Message, type_name="geometry_msgs/msg/Pose"):
    """geometry_msgs/msg/Pose: A position and an orientation."""

    __slots__ = (
        "position",
        "orientation",
    )
    position: Point
    orientation: Quaternion

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            position: Point = ...,
            orientation: Quaternion = ...,
        ) -> None: ...


class PoseStamped(Message, type_name="geometry_msgs/msg/PoseStamped"):
    """geometry_msgs/msg/PoseStamped: A pose with a time and a frame."""

    __slots__ = (
        "header",
        "pose",
    )
    header: Header
    pose: Pose

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            pose: Pose = ...,
        ) -> None: ...


class Vector3(Message, type_name="geometry_msgs/msg/Vector3"):
    """geometry_msgs/msg/Vector3: A direction and magnitude in free space (metres, metres per second ... as the topic says)."""

    __slots__ = (
        "x",
        "y",
        "z",
    )
    x: float
    y: float
    z: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            x: float = ...,
            y: float = ...,
            z: float = ...,
        ) -> None: ...


class Transform(Message, type_name="geometry_msgs/msg/Transform"):
    """geometry_msgs/msg/Transform: Where one frame sits in another: a translation (metres) and a rotation."""

    __slots__ = (
        "translation",
        "rotation",
    )
    translation: Vector3
    rotation: Quaternion

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            translation: Vector3 = ...,
            rotation: Quaternion = ...,
        ) -> None: ...


class TransformStamped(Message, type_name="geometry_msgs/msg/TransformStamped"):
    """geometry_msgs/msg/TransformStamped: The transform from header.frame_id to child_frame_id, at header.stamp."""

    __slots__ = (
        "header",
        "child_frame_id",
        "transform",
    )
    header: Header
    child_frame_id: str
    transform: Transform

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            child_frame_id: str = ...,
            transform: Transform = ...,
        ) -> None: ...


class Twist(Message, type_name="geometry_msgs/msg/Twist"):
    """geometry_msgs/msg/Twist: Velocity: linear (m/s) and angular (rad/s)."""

    __slots__ = (
        "linear",
        "angular",
    )
    linear: Vector3
    angular: Vector3

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            linear: Vector3 = ...,
            angular: Vector3 = ...,
        ) -> None: ...


class TwistStamped(Message, type_name="geometry_msgs/msg/TwistStamped"):
    """geometry_msgs/msg/TwistStamped: A velocity with a time and a frame."""

    __slots__ = (
        "header",
        "twist",
    )
    header: Header
    twist: Twist

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            twist: Twist = ...,
        ) -> None: ...


class Vector3Stamped(Message, type_name="geometry_msgs/msg/Vector3Stamped"):
    """geometry_msgs/msg/Vector3Stamped: A vector with a time and a frame."""

    __slots__ = (
        "header",
        "vector",
    )
    header: Header
    vector: Vector3

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            vector: Vector3 = ...,
        ) -> None: ...


__all__ = [
    "Point",
    "PointStamped",
    "Pose",
    "PoseStamped",
    "Quaternion",
    "Transform",
    "TransformStamped",
    "Twist",
    "TwistStamped",
    "Vector3",
    "Vector3Stamped",
]
