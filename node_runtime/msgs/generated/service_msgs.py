"""service_msgs: generated from ROS 2's definitions (the wheels node_runtime/msgs/ros_packages.txt pins) by `python -m node_runtime.msgs.generate`; do not edit."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any, ClassVar

if TYPE_CHECKING:
    import numpy as np
    import numpy.typing as npt

from node_runtime.msgs._base import Message
from node_runtime.msgs.generated.builtin_interfaces import Time


class ServiceEventInfo(Message, type_name="service_msgs/msg/ServiceEventInfo"):
    """service_msgs/msg/ServiceEventInfo: The type of event this message represents"""

    __slots__ = (
        "event_type",
        "stamp",
        "client_gid",
        "sequence_number",
    )
    REQUEST_SENT: ClassVar[int]
    REQUEST_RECEIVED: ClassVar[int]
    RESPONSE_SENT: ClassVar[int]
    RESPONSE_RECEIVED: ClassVar[int]
    event_type: int
    stamp: Time
    client_gid: npt.NDArray[np.uint8]
    sequence_number: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            event_type: int = ...,
            stamp: Time = ...,
            client_gid: Sequence[int] | npt.NDArray[Any] = ...,
            sequence_number: int = ...,
        ) -> None: ...


__all__ = [
    "ServiceEventInfo",
]
