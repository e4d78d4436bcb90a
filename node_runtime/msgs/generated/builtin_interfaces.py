"""builtin_interfaces: generated from ROS 2's definitions (the wheels node_runtime/msgs/ros_packages.txt pins) by `python -m node_runtime.msgs.generate`; do not edit."""

from __future__ import annotations

from typing import TYPE_CHECKING

from node_runtime.msgs._base import Message


class Duration(Message, type_name="builtin_interfaces/msg/Duration"):
    """builtin_interfaces/msg/Duration: Duration defines a period between two time points."""

    __slots__ = (
        "sec",
        "nanosec",
    )
    sec: int
    nanosec: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            sec: int = ...,
            nanosec: int = ...,
        ) -> None: ...


class Time(Message, type_name="builtin_interfaces/msg/Time"):
    """builtin_interfaces/msg/Time: This message communicates ROS Time defined here:"""

    __slots__ = (
        "sec",
        "nanosec",
    )
    sec: int
    nanosec: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            sec: int = ...,
            nanosec: int = ...,
        ) -> None: ...


__all__ = [
    "Duration",
    "Time",
]
