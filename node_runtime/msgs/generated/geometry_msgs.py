"""geometry_msgs: generated from ROS 2's definitions (the wheels node_runtime/msgs/ros_packages.txt pins) by `python -m node_runtime.msgs.generate`; do not edit."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import numpy as np
    import numpy.typing as npt

from node_runtime.msgs._base import Message
from node_runtime.msgs.generated.std_msgs import Header


class Vector3(Message, type_name="geometry_msgs/msg/Vector3"):
    """geometry_msgs/msg/Vector3: This represents a vector in free space."""

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


class Accel(Message, type_name="geometry_msgs/msg/Accel"):
    """geometry_msgs/msg/Accel: This expresses acceleration in free space broken into its linear and angular parts."""

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


class AccelStamped(Message, type_name="geometry_msgs/msg/AccelStamped"):
    """geometry_msgs/msg/AccelStamped: An accel with reference coordinate frame and timestamp"""

    __slots__ = (
        "header",
        "accel",
    )
    header: Header
    accel: Accel

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            accel: Accel = ...,
        ) -> None: ...


class AccelWithCovariance(Message, type_name="geometry_msgs/msg/AccelWithCovariance"):
    """geometry_msgs/msg/AccelWithCovariance: This expresses acceleration in free space with uncertainty."""

    __slots__ = (
        "accel",
        "covariance",
    )
    accel: Accel
    covariance: npt.NDArray[np.float64]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            accel: Accel = ...,
            covariance: Sequence[float] | npt.NDArray[Any] = ...,
        ) -> None: ...


class AccelWithCovarianceStamped(Message, type_name="geometry_msgs/msg/AccelWithCovarianceStamped"):
    """geometry_msgs/msg/AccelWithCovarianceStamped: This represents an estimated accel with reference coordinate frame and timestamp."""

    __slots__ = (
        "header",
        "accel",
    )
    header: Header
    accel: AccelWithCovariance

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            accel: AccelWithCovariance = ...,
        ) -> None: ...


class Inertia(Message, type_name="geometry_msgs/msg/Inertia"):
    """geometry_msgs/msg/Inertia: Mass [kg]"""

    __slots__ = (
        "m",
        "com",
        "ixx",
        "ixy",
        "ixz",
        "iyy",
        "iyz",
        "izz",
    )
    m: float
    com: Vector3
    ixx: float
    ixy: float
    ixz: float
    iyy: float
    iyz: float
    izz: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            m: float = ...,
            com: Vector3 = ...,
            ixx: float = ...,
            ixy: float = ...,
            ixz: float = ...,
            iyy: float = ...,
            iyz: float = ...,
            izz: float = ...,
        ) -> None: ...


class InertiaStamped(Message, type_name="geometry_msgs/msg/InertiaStamped"):
    """geometry_msgs/msg/InertiaStamped: An Inertia with a time stamp and reference frame."""

    __slots__ = (
        "header",
        "inertia",
    )
    header: Header
    inertia: Inertia

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            inertia: Inertia = ...,
        ) -> None: ...


class Point(Message, type_name="geometry_msgs/msg/Point"):
    """geometry_msgs/msg/Point: This contains the position of a point in free space"""

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


class Point32(Message, type_name="geometry_msgs/msg/Point32"):
    """geometry_msgs/msg/Point32: This contains the position of a point in free space(with 32 bits of precision)."""

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
    """geometry_msgs/msg/PointStamped: This represents a Point with reference coordinate frame and timestamp"""

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


class Polygon(Message, type_name="geometry_msgs/msg/Polygon"):
    """geometry_msgs/msg/Polygon: A specification of a polygon where the first and last points are assumed to be connected"""

    __slots__ = ("points",)
    points: list[Point32]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            points: Sequence[Point32] = ...,
        ) -> None: ...


class PolygonInstance(Message, type_name="geometry_msgs/msg/PolygonInstance"):
    """geometry_msgs/msg/PolygonInstance: A specification of a polygon where the first and last points are assumed to be connected"""

    __slots__ = (
        "polygon",
        "id",
    )
    polygon: Polygon
    id: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            polygon: Polygon = ...,
            id: int = ...,
        ) -> None: ...


class PolygonInstanceStamped(Message, type_name="geometry_msgs/msg/PolygonInstanceStamped"):
    """geometry_msgs/msg/PolygonInstanceStamped: This represents a Polygon with reference coordinate frame and timestamp"""

    __slots__ = (
        "header",
        "polygon",
    )
    header: Header
    polygon: PolygonInstance

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            polygon: PolygonInstance = ...,
        ) -> None: ...


class PolygonStamped(Message, type_name="geometry_msgs/msg/PolygonStamped"):
    """geometry_msgs/msg/PolygonStamped: This represents a Polygon with reference coordinate frame and timestamp"""

    __slots__ = (
        "header",
        "polygon",
    )
    header: Header
    polygon: Polygon

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            polygon: Polygon = ...,
        ) -> None: ...


class Quaternion(Message, type_name="geometry_msgs/msg/Quaternion"):
    """geometry_msgs/msg/Quaternion: This represents an orientation in free space in quaternion form."""

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
    """geometry_msgs/msg/Pose: A representation of pose in free space, composed of position and orientation."""

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


class Pose2D(Message, type_name="geometry_msgs/msg/Pose2D"):
    """geometry_msgs/msg/Pose2D: Deprecated as of Foxy and will potentially be removed in any following release."""

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


class PoseArray(Message, type_name="geometry_msgs/msg/PoseArray"):
    """geometry_msgs/msg/PoseArray: An array of poses with a header for global reference."""

    __slots__ = (
        "header",
        "poses",
    )
    header: Header
    poses: list[Pose]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            poses: Sequence[Pose] = ...,
        ) -> None: ...


class PoseStamped(Message, type_name="geometry_msgs/msg/PoseStamped"):
    """geometry_msgs/msg/PoseStamped: A Pose with reference coordinate frame and timestamp"""

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


class PoseWithCovariance(Message, type_name="geometry_msgs/msg/PoseWithCovariance"):
    """geometry_msgs/msg/PoseWithCovariance: This represents a pose in free space with uncertainty."""

    __slots__ = (
        "pose",
        "covariance",
    )
    pose: Pose
    covariance: npt.NDArray[np.float64]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            pose: Pose = ...,
            covariance: Sequence[float] | npt.NDArray[Any] = ...,
        ) -> None: ...


class PoseWithCovarianceStamped(Message, type_name="geometry_msgs/msg/PoseWithCovarianceStamped"):
    """geometry_msgs/msg/PoseWithCovarianceStamped: This expresses an estimated pose with a reference coordinate frame and timestamp"""

    __slots__ = (
        "header",
        "pose",
    )
    header: Header
    pose: PoseWithCovariance

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            pose: PoseWithCovariance = ...,
        ) -> None: ...


class QuaternionStamped(Message, type_name="geometry_msgs/msg/QuaternionStamped"):
    """geometry_msgs/msg/QuaternionStamped: This represents an orientation with reference coordinate frame and timestamp."""

    __slots__ = (
        "header",
        "quaternion",
    )
    header: Header
    quaternion: Quaternion

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            quaternion: Quaternion = ...,
        ) -> None: ...


class Transform(Message, type_name="geometry_msgs/msg/Transform"):
    """geometry_msgs/msg/Transform: This represents the transform between two coordinate frames in free space."""

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
    """geometry_msgs/msg/TransformStamped: This expresses a transform from coordinate frame header.frame_id"""

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
    """geometry_msgs/msg/Twist: This expresses velocity in free space broken into its linear and angular parts."""

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
    """geometry_msgs/msg/TwistStamped: A twist with reference coordinate frame and timestamp"""

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


class TwistWithCovariance(Message, type_name="geometry_msgs/msg/TwistWithCovariance"):
    """geometry_msgs/msg/TwistWithCovariance: This expresses velocity in free space with uncertainty."""

    __slots__ = (
        "twist",
        "covariance",
    )
    twist: Twist
    covariance: npt.NDArray[np.float64]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            twist: Twist = ...,
            covariance: Sequence[float] | npt.NDArray[Any] = ...,
        ) -> None: ...


class TwistWithCovarianceStamped(Message, type_name="geometry_msgs/msg/TwistWithCovarianceStamped"):
    """geometry_msgs/msg/TwistWithCovarianceStamped: This represents an estimated twist with reference coordinate frame and timestamp."""

    __slots__ = (
        "header",
        "twist",
    )
    header: Header
    twist: TwistWithCovariance

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            twist: TwistWithCovariance = ...,
        ) -> None: ...


class Vector3Stamped(Message, type_name="geometry_msgs/msg/Vector3Stamped"):
    """geometry_msgs/msg/Vector3Stamped: This represents a Vector3 with reference coordinate frame and timestamp"""

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


class VelocityStamped(Message, type_name="geometry_msgs/msg/VelocityStamped"):
    """geometry_msgs/msg/VelocityStamped: This expresses the timestamped velocity vector of a frame 'body_frame_id' in the reference frame 'reference_frame_id' expressed from arbitrary observation frame 'header.frame_id'."""

    __slots__ = (
        "header",
        "body_frame_id",
        "reference_frame_id",
        "velocity",
    )
    header: Header
    body_frame_id: str
    reference_frame_id: str
    velocity: Twist

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            body_frame_id: str = ...,
            reference_frame_id: str = ...,
            velocity: Twist = ...,
        ) -> None: ...


class Wrench(Message, type_name="geometry_msgs/msg/Wrench"):
    """geometry_msgs/msg/Wrench: This represents force in free space, separated into its linear and angular parts."""

    __slots__ = (
        "force",
        "torque",
    )
    force: Vector3
    torque: Vector3

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            force: Vector3 = ...,
            torque: Vector3 = ...,
        ) -> None: ...


class WrenchStamped(Message, type_name="geometry_msgs/msg/WrenchStamped"):
    """geometry_msgs/msg/WrenchStamped: A wrench with reference coordinate frame and timestamp"""

    __slots__ = (
        "header",
        "wrench",
    )
    header: Header
    wrench: Wrench

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            wrench: Wrench = ...,
        ) -> None: ...


__all__ = [
    "Accel",
    "AccelStamped",
    "AccelWithCovariance",
    "AccelWithCovarianceStamped",
    "Inertia",
    "InertiaStamped",
    "Point",
    "Point32",
    "PointStamped",
    "Polygon",
    "PolygonInstance",
    "PolygonInstanceStamped",
    "PolygonStamped",
    "Pose",
    "Pose2D",
    "PoseArray",
    "PoseStamped",
    "PoseWithCovariance",
    "PoseWithCovarianceStamped",
    "Quaternion",
    "QuaternionStamped",
    "Transform",
    "TransformStamped",
    "Twist",
    "TwistStamped",
    "TwistWithCovariance",
    "TwistWithCovarianceStamped",
    "Vector3",
    "Vector3Stamped",
    "VelocityStamped",
    "Wrench",
    "WrenchStamped",
]
