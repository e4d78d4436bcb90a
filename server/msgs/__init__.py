"""Message types with their ROS 2 names (``std_msgs/msg/Bool`` ...) and a registry to look them up."""

from ._base import Field, Message, MessageError
from .registry import UnknownTypeError, get_type, normalize_type_name, type_names
from .types import (
    KEY_CONSTANTS,
    Bool,
    Float64,
    Header,
    Int64,
    Key,
    Log,
    Point,
    Pose,
    PoseStamped,
    Quaternion,
    String,
    Time,
    Twist,
    TwistStamped,
    Vector3,
)  # fmt: skip

__all__ = [
    "KEY_CONSTANTS", "Bool", "Field", "Float64", "Header", "Int64", "Key", "Log", "Message",
    "MessageError", "Point", "Pose", "PoseStamped", "Quaternion", "String", "Time", "Twist",
    "TwistStamped", "UnknownTypeError", "Vector3", "get_type", "normalize_type_name", "type_names",
]  # fmt: skip
