"""stereo_msgs: generated from ROS 2's definitions (the wheels node_runtime/msgs/ros_packages.txt pins) by `python -m node_runtime.msgs.generate`; do not edit."""

from __future__ import annotations

from typing import TYPE_CHECKING

from node_runtime.msgs._base import Message
from node_runtime.msgs.generated.sensor_msgs import Image, RegionOfInterest
from node_runtime.msgs.generated.std_msgs import Header


class DisparityImage(Message, type_name="stereo_msgs/msg/DisparityImage"):
    """stereo_msgs/msg/DisparityImage: Separate header for compatibility with current TimeSynchronizer."""

    __slots__ = (
        "header",
        "image",
        "f",
        "t",
        "valid_window",
        "min_disparity",
        "max_disparity",
        "delta_d",
    )
    header: Header
    image: Image
    f: float
    t: float
    valid_window: RegionOfInterest
    min_disparity: float
    max_disparity: float
    delta_d: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            image: Image = ...,
            f: float = ...,
            t: float = ...,
            valid_window: RegionOfInterest = ...,
            min_disparity: float = ...,
            max_disparity: float = ...,
            delta_d: float = ...,
        ) -> None: ...


__all__ = [
    "DisparityImage",
]
