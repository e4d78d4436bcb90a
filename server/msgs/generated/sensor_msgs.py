"""sensor_msgs: generated from server/msgs/interfaces/sensor_msgs by `python -m server.msgs.generate`; do not edit."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import numpy as np
    import numpy.typing as npt

from .._base import Message
from .geometry_msgs import Quaternion, Vector3
from .std_msgs import Header


class Imu(Message, type_name="sensor_msgs/msg/Imu"):
    """sensor_msgs/msg/Imu: An inertial measurement. A covariance row-major about x, y, z; all zeros means unknown,"""

    __slots__ = (
        "header",
        "orientation",
        "orientation_covariance",
        "angular_velocity",
        "angular_velocity_covariance",
        "linear_acceleration",
        "linear_acceleration_covariance",
    )
    header: Header
    orientation: Quaternion
    orientation_covariance: npt.NDArray[np.float64]
    angular_velocity: Vector3
    angular_velocity_covariance: npt.NDArray[np.float64]
    linear_acceleration: Vector3
    linear_acceleration_covariance: npt.NDArray[np.float64]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            orientation: Quaternion = ...,
            orientation_covariance: Sequence[float] | npt.NDArray[Any] = ...,
            angular_velocity: Vector3 = ...,
            angular_velocity_covariance: Sequence[float] | npt.NDArray[Any] = ...,
            linear_acceleration: Vector3 = ...,
            linear_acceleration_covariance: Sequence[float] | npt.NDArray[Any] = ...,
        ) -> None: ...


__all__ = [
    "Imu",
]
