"""launch_xml: ROS 2's XML frontend for launch files, as a Python launch file includes one."""

from launch_xml import launch_description_sources

__all__ = ["launch_description_sources"]
