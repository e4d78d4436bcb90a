"""builtin_interfaces: generated from server/msgs/interfaces/builtin_interfaces by `python -m server.msgs.generate`; do not edit."""

from __future__ import annotations

from typing import TYPE_CHECKING

from .._base import Message


class Duration(Message, type_name="builtin_interfaces/msg/Duration"):
    """builtin_interfaces/msg/Duration: A span of time: whole seconds (may be negative) and nanoseconds."""

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
    """builtin_interfaces/msg/Time: A point in time: whole seconds and nanoseconds since the epoch (or since the clock's start)."""

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
