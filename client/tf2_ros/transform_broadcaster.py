"""tf2_ros' TransformBroadcaster: moving frames on ``/tf``."""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from geometry_msgs.msg import TransformStamped
from rclpy.qos import QoSProfile
from tf2_msgs.msg import TFMessage


def as_list(transform: TransformStamped | Iterable[TransformStamped]) -> list[TransformStamped]:
    """One transform or several, as tf2_ros' ``sendTransform`` takes them."""
    if isinstance(transform, list):
        return transform
    if isinstance(transform, TransformStamped):
        return [transform]
    return list(transform)


class TransformBroadcaster:
    """Publishes TFMessages on ``/tf`` (a keep-last 100 profile unless ``qos`` says otherwise)."""

    def __init__(self, node: Any, qos: QoSProfile | int | None = None) -> None:
        self.pub_tf = node.create_publisher(TFMessage, "/tf", QoSProfile(depth=100) if qos is None else qos)

    def sendTransform(self, transform: TransformStamped | Iterable[TransformStamped]) -> None:
        """Send one transform, or a list of them, in one message."""
        self.pub_tf.publish(TFMessage(transforms=as_list(transform)))


__all__ = ["TransformBroadcaster"]
