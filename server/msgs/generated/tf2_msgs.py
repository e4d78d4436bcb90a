"""tf2_msgs: generated from server/msgs/interfaces/tf2_msgs by `python -m server.msgs.generate`; do not edit."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from .._base import Message
from .geometry_msgs import TransformStamped


class TFMessage(Message, type_name="tf2_msgs/msg/TFMessage"):
    """tf2_msgs/msg/TFMessage: A batch of transforms, as /tf carries them."""

    __slots__ = ("transforms",)
    transforms: list[TransformStamped]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            transforms: Sequence[TransformStamped] = ...,
        ) -> None: ...


__all__ = [
    "TFMessage",
]
