"""tf2_ros for a node process: frames and the transforms between them over time.

``TransformBroadcaster`` and ``StaticTransformBroadcaster`` publish on ``/tf`` and ``/tf_static``;
a ``TransformListener`` fills a ``Buffer`` from both, which answers ``lookup_transform``,
``can_transform`` and ``wait_for_transform_async`` with tf2's interpolation and exceptions. The
modules are tf2_ros' own names (``tf2_ros.buffer``, ``tf2_ros.transform_listener``, ...), so
tutorials import them as they do on ROS 2.
"""

from tf2_ros._exceptions import (
    ConnectivityException,
    ExtrapolationException,
    InvalidArgumentException,
    LookupException,
    TimeoutException,
    TransformException,
)
from tf2_ros.buffer import Buffer
from tf2_ros.buffer_interface import (
    BufferInterface,
    NotImplementedException,
    TransformRegistration,
    TypeException,
)
from tf2_ros.static_transform_broadcaster import StaticTransformBroadcaster
from tf2_ros.transform_broadcaster import TransformBroadcaster
from tf2_ros.transform_listener import TransformListener

__all__ = [
    "Buffer",
    "BufferInterface",
    "ConnectivityException",
    "ExtrapolationException",
    "InvalidArgumentException",
    "LookupException",
    "NotImplementedException",
    "StaticTransformBroadcaster",
    "TimeoutException",
    "TransformBroadcaster",
    "TransformException",
    "TransformListener",
    "TransformRegistration",
    "TypeException",
]
