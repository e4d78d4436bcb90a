"""The message types the lab's own nodes use, by their class names (defined in node_runtime/msgs/generated)."""

from __future__ import annotations

from node_runtime.msgs._base import Message
from node_runtime.msgs.generated.builtin_interfaces import Duration, Time
from node_runtime.msgs.generated.geometry_msgs import (
    Point,
    PointStamped,
    Pose,
    PoseStamped,
    Quaternion,
    Transform,
    TransformStamped,
    Twist,
    TwistStamped,
    Vector3,
    Vector3Stamped,
)
from node_runtime.msgs.generated.keyboard_msgs import Key
from node_runtime.msgs.generated.rcl_interfaces import Log
from node_runtime.msgs.generated.sensor_msgs import Imu
from node_runtime.msgs.generated.std_msgs import (
    Bool,
    ColorRGBA,
    Empty,
    Float32,
    Float64,
    Header,
    Int32,
    Int64,
    String,
)
from node_runtime.msgs.generated.tf2_msgs import TFMessage

# Key's KEY_* and MODIFIER_* constants by name, as its definition declares them.
KEY_CONSTANTS: dict[str, int] = {c.name: c.value for c in Key.SPEC.constants}

ALL_TYPES: tuple[type[Message], ...] = (
    Time,
    Duration,
    Header,
    Bool,
    Empty,
    Int32,
    Int64,
    Float32,
    Float64,
    String,
    ColorRGBA,
    Vector3,
    Vector3Stamped,
    Point,
    PointStamped,
    Quaternion,
    Pose,
    PoseStamped,
    Twist,
    TwistStamped,
    Transform,
    TransformStamped,
    TFMessage,
    Imu,
    Key,
    Log,
)

__all__ = [
    "ALL_TYPES",
    "KEY_CONSTANTS",
    "Bool",
    "ColorRGBA",
    "Duration",
    "Empty",
    "Float32",
    "Float64",
    "Header",
    "Imu",
    "Int32",
    "Int64",
    "Key",
    "Log",
    "Point",
    "PointStamped",
    "Pose",
    "PoseStamped",
    "Quaternion",
    "String",
    "TFMessage",
    "Time",
    "Transform",
    "TransformStamped",
    "Twist",
    "TwistStamped",
    "Vector3",
    "Vector3Stamped",
]
