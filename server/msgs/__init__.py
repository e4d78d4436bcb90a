"""Message and service types with their ROS 2 names (``std_msgs/msg/Bool`` ...), declared once in
``.msg``/``.srv`` files (server/msgs/interfaces, and a workspace's interface packages added at run
time through server.msgs.catalog) and looked up by name."""

from ._base import Field, Message, MessageError, Service
from .registry import (
    UnknownTypeError,
    get_service_type,
    get_type,
    normalize_type_name,
    service_names,
    type_names,
)  # fmt: skip
from .types import (
    ALL_TYPES,
    KEY_CONSTANTS,
    Bool,
    ColorRGBA,
    Duration,
    Empty,
    Float32,
    Float64,
    Header,
    Imu,
    Int32,
    Int64,
    Key,
    Log,
    Point,
    PointStamped,
    Pose,
    PoseStamped,
    Quaternion,
    String,
    TFMessage,
    Time,
    Transform,
    TransformStamped,
    Twist,
    TwistStamped,
    Vector3,
    Vector3Stamped,
)  # fmt: skip

__all__ = [
    "ALL_TYPES", "KEY_CONSTANTS", "Bool", "ColorRGBA", "Duration", "Empty", "Field", "Float32",
    "Float64", "Header", "Imu", "Int32", "Int64", "Key", "Log", "Message", "MessageError", "Point",
    "PointStamped", "Pose", "PoseStamped", "Quaternion", "Service", "String", "TFMessage", "Time",
    "Transform", "TransformStamped", "Twist", "TwistStamped", "UnknownTypeError", "Vector3",
    "Vector3Stamped", "get_service_type", "get_type", "normalize_type_name", "service_names",
    "type_names",
]  # fmt: skip
