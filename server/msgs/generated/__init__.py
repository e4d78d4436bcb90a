"""The message and service classes, one module per ROS package (see server/msgs/generate.py)."""

from . import (
    builtin_interfaces,
    example_interfaces,
    geometry_msgs,
    keyboard_msgs,
    rcl_interfaces,
    sensor_msgs,
    service_msgs,
    std_msgs,
    std_srvs,
    tf2_msgs,
)

__all__ = [
    "builtin_interfaces",
    "example_interfaces",
    "geometry_msgs",
    "keyboard_msgs",
    "rcl_interfaces",
    "sensor_msgs",
    "service_msgs",
    "std_msgs",
    "std_srvs",
    "tf2_msgs",
]
