"""rcl_interfaces: generated from server/msgs/interfaces/rcl_interfaces by `python -m server.msgs.generate`; do not edit."""

from __future__ import annotations

from typing import TYPE_CHECKING, ClassVar

from .._base import Message
from .builtin_interfaces import Time


class Log(Message, type_name="rcl_interfaces/msg/Log"):
    """rcl_interfaces/msg/Log: One log line, as every node publishes it on /rosout. Severity levels:"""

    __slots__ = (
        "stamp",
        "level",
        "name",
        "msg",
        "file",
        "function",
        "line",
    )
    DEBUG: ClassVar[int]
    INFO: ClassVar[int]
    WARN: ClassVar[int]
    ERROR: ClassVar[int]
    FATAL: ClassVar[int]
    stamp: Time
    level: int
    name: str
    msg: str
    file: str
    function: str
    line: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            stamp: Time = ...,
            level: int = ...,
            name: str = ...,
            msg: str = ...,
            file: str = ...,
            function: str = ...,
            line: int = ...,
        ) -> None: ...


__all__ = [
    "Log",
]
