"""launch_ros's actions, under ROS 2's names."""

from .node import Node
from .ros_settings import PushROSNamespace, PushRosNamespace, SetParameter, SetRemap

__all__ = ["Node", "PushROSNamespace", "PushRosNamespace", "SetParameter", "SetRemap"]
