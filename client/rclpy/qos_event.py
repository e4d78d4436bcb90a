"""``rclpy.qos_event``: the old name of ``rclpy.event_handler``, which rclpy still answers to with
a warning."""

import warnings

from rclpy.event_handler import *  # noqa: F403
from rclpy.event_handler import __all__ as __all__

warnings.warn("importing 'qos_event' is deprecated; import 'event_handler' instead", stacklevel=2)
