"""rosgraph_msgs: generated from ROS 2's definitions (the wheels node_runtime/msgs/ros_packages.txt pins) by `python -m node_runtime.msgs.generate`; do not edit."""

from __future__ import annotations

from typing import TYPE_CHECKING

from node_runtime.msgs._base import Message
from node_runtime.msgs.generated.builtin_interfaces import Time


class Clock(Message, type_name="rosgraph_msgs/msg/Clock"):
    """rosgraph_msgs/msg/Clock: This message communicates the current time."""

    __slots__ = ("clock",)
    clock: Time

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            clock: Time = ...,
        ) -> None: ...


__all__ = [
    "Clock",
]
