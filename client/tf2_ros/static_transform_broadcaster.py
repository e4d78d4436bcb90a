"""tf2_ros' StaticTransformBroadcaster: frames fixed for all time, on ``/tf_static``.

The topic is transient local with a depth of 1, so the one message a broadcaster keeps must hold
all of its frames: each ``sendTransform`` adds its transforms to the broadcaster's set (replacing
one with the same child frame) and publishes the whole set again. A listener that starts later
gets that message from the publisher's cache.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from geometry_msgs.msg import TransformStamped
from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile
from tf2_msgs.msg import TFMessage

from tf2_ros.transform_broadcaster import as_list


class StaticTransformBroadcaster:
    def __init__(self, node: Any, qos: QoSProfile | int | None = None) -> None:
        if qos is None:
            qos = QoSProfile(
                depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL, history=HistoryPolicy.KEEP_LAST
            )
        self.pub_tf = node.create_publisher(TFMessage, "/tf_static", qos)
        self.net_message = TFMessage()

    def sendTransform(self, transform: TransformStamped | Iterable[TransformStamped]) -> None:
        for new in as_list(transform):
            kept = self.net_message.transforms
            same = next((i for i, old in enumerate(kept) if old.child_frame_id == new.child_frame_id), None)
            if same is None:
                kept.append(new)
            else:
                kept[same] = new
        self.pub_tf.publish(self.net_message)


__all__ = ["StaticTransformBroadcaster"]
