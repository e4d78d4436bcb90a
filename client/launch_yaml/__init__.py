"""launch_yaml: ROS 2's YAML frontend for launch files, as a Python launch file includes one."""

from launch_yaml import launch_description_sources

__all__ = ["launch_description_sources"]
