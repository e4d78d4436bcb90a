"""std_msgs: generated from server/msgs/interfaces/std_msgs by `python -m server.msgs.generate`; do not edit."""

from __future__ import annotations

from typing import TYPE_CHECKING

from .._base import Message
from .builtin_interfaces import Time


class Bool(Message, type_name="std_msgs/msg/Bool"):
    """std_msgs/msg/Bool"""

    __slots__ = ("data",)
    data: bool

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: bool = ...,
        ) -> None: ...


class Byte(Message, type_name="std_msgs/msg/Byte"):
    """std_msgs/msg/Byte"""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


class Char(Message, type_name="std_msgs/msg/Char"):
    """std_msgs/msg/Char"""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


class ColorRGBA(Message, type_name="std_msgs/msg/ColorRGBA"):
    """std_msgs/msg/ColorRGBA: A colour, each channel from 0 to 1."""

    __slots__ = (
        "r",
        "g",
        "b",
        "a",
    )
    r: float
    g: float
    b: float
    a: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            r: float = ...,
            g: float = ...,
            b: float = ...,
            a: float = ...,
        ) -> None: ...


class Empty(Message, type_name="std_msgs/msg/Empty"):
    """std_msgs/msg/Empty"""

    __slots__ = ()


class Float32(Message, type_name="std_msgs/msg/Float32"):
    """std_msgs/msg/Float32"""

    __slots__ = ("data",)
    data: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: float = ...,
        ) -> None: ...


class Float64(Message, type_name="std_msgs/msg/Float64"):
    """std_msgs/msg/Float64"""

    __slots__ = ("data",)
    data: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: float = ...,
        ) -> None: ...


class Header(Message, type_name="std_msgs/msg/Header"):
    """std_msgs/msg/Header: When and in which coordinate frame data was taken."""

    __slots__ = (
        "stamp",
        "frame_id",
    )
    stamp: Time
    frame_id: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            stamp: Time = ...,
            frame_id: str = ...,
        ) -> None: ...


class Int16(Message, type_name="std_msgs/msg/Int16"):
    """std_msgs/msg/Int16"""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


class Int32(Message, type_name="std_msgs/msg/Int32"):
    """std_msgs/msg/Int32"""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


class Int64(Message, type_name="std_msgs/msg/Int64"):
    """std_msgs/msg/Int64"""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


class Int8(Message, type_name="std_msgs/msg/Int8"):
    """std_msgs/msg/Int8"""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


class String(Message, type_name="std_msgs/msg/String"):
    """std_msgs/msg/String"""

    __slots__ = ("data",)
    data: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: str = ...,
        ) -> None: ...


class UInt16(Message, type_name="std_msgs/msg/UInt16"):
    """std_msgs/msg/UInt16"""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


class UInt32(Message, type_name="std_msgs/msg/UInt32"):
    """std_msgs/msg/UInt32"""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


class UInt64(Message, type_name="std_msgs/msg/UInt64"):
    """std_msgs/msg/UInt64"""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


class UInt8(Message, type_name="std_msgs/msg/UInt8"):
    """std_msgs/msg/UInt8"""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


__all__ = [
    "Bool",
    "Byte",
    "Char",
    "ColorRGBA",
    "Empty",
    "Float32",
    "Float64",
    "Header",
    "Int16",
    "Int32",
    "Int64",
    "Int8",
    "String",
    "UInt16",
    "UInt32",
    "UInt64",
    "UInt8",
]
