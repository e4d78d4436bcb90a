"""launch_ros's actions, under ROS 2's names."""

from launch_ros.actions.node import Node
from launch_ros.actions.ros_settings import PushROSNamespace, PushRosNamespace, SetParameter, SetRemap

__all__ = ["Node", "PushROSNamespace", "PushRosNamespace", "SetParameter", "SetRemap"]
