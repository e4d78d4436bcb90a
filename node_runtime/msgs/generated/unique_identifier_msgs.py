"""unique_identifier_msgs: generated from ROS 2's definitions (the wheels node_runtime/msgs/ros_packages.txt pins) by `python -m node_runtime.msgs.generate`; do not edit."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import numpy as np
    import numpy.typing as npt

from node_runtime.msgs._base import Message


class UUID(Message, type_name="unique_identifier_msgs/msg/UUID"):
    """unique_identifier_msgs/msg/UUID: A universally unique identifier (UUID)."""

    __slots__ = ("uuid",)
    uuid: npt.NDArray[np.uint8]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            uuid: Sequence[int] | npt.NDArray[Any] = ...,
        ) -> None: ...


__all__ = [
    "UUID",
]
