"""ROS 2's ``launch_ros`` for a lab: ``Node`` and the ROS-specific actions and substitutions of a
``.launch.py`` file, under the same names (see ``launch``)."""

from launch_ros import actions, parameter_descriptions, substitutions

__all__ = ["actions", "parameter_descriptions", "substitutions"]
