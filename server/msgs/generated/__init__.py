"""The message and service classes, one module per ROS package (see server/msgs/generate.py)."""

from . import (
    action_msgs,
    action_tutorials_interfaces,
    builtin_interfaces,
    example_interfaces,
    geometry_msgs,
    keyboard_msgs,
    rcl_interfaces,
    rosapi_msgs,
    sensor_msgs,
    service_msgs,
    std_msgs,
    std_srvs,
    tf2_msgs,
    turtlesim,
    unique_identifier_msgs,
)

__all__ = [
    "action_msgs",
    "action_tutorials_interfaces",
    "builtin_interfaces",
    "example_interfaces",
    "geometry_msgs",
    "keyboard_msgs",
    "rcl_interfaces",
    "rosapi_msgs",
    "sensor_msgs",
    "service_msgs",
    "std_msgs",
    "std_srvs",
    "tf2_msgs",
    "turtlesim",
    "unique_identifier_msgs",
]
