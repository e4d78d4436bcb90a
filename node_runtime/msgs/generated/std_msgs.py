"""std_msgs: generated from ROS 2's definitions (the wheels node_runtime/msgs/ros_packages.txt pins) by `python -m node_runtime.msgs.generate`; do not edit."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import numpy.typing as npt

from node_runtime.msgs._base import Message
from node_runtime.msgs._field import FloatArray, IntArray
from node_runtime.msgs.generated.builtin_interfaces import Time


class Bool(Message, type_name="std_msgs/msg/Bool"):
    """std_msgs/msg/Bool: This was originally provided as an example message."""

    __slots__ = ("data",)
    data: bool

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: bool = ...,
        ) -> None: ...


class Byte(Message, type_name="std_msgs/msg/Byte"):
    """std_msgs/msg/Byte: This was originally provided as an example message."""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


class MultiArrayDimension(Message, type_name="std_msgs/msg/MultiArrayDimension"):
    """std_msgs/msg/MultiArrayDimension: This was originally provided as an example message."""

    __slots__ = (
        "label",
        "size",
        "stride",
    )
    label: str
    size: int
    stride: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            label: str = ...,
            size: int = ...,
            stride: int = ...,
        ) -> None: ...


class MultiArrayLayout(Message, type_name="std_msgs/msg/MultiArrayLayout"):
    """std_msgs/msg/MultiArrayLayout: This was originally provided as an example message."""

    __slots__ = (
        "dim",
        "data_offset",
    )
    dim: list[MultiArrayDimension]
    data_offset: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            dim: Sequence[MultiArrayDimension] = ...,
            data_offset: int = ...,
        ) -> None: ...


class ByteMultiArray(Message, type_name="std_msgs/msg/ByteMultiArray"):
    """std_msgs/msg/ByteMultiArray: This was originally provided as an example message."""

    __slots__ = (
        "layout",
        "data",
    )
    layout: MultiArrayLayout
    data: IntArray

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            layout: MultiArrayLayout = ...,
            data: Sequence[int] | npt.NDArray[Any] = ...,
        ) -> None: ...


class Char(Message, type_name="std_msgs/msg/Char"):
    """std_msgs/msg/Char: This was originally provided as an example message."""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


class ColorRGBA(Message, type_name="std_msgs/msg/ColorRGBA"):
    """std_msgs/msg/ColorRGBA"""

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
    """std_msgs/msg/Float32: This was originally provided as an example message."""

    __slots__ = ("data",)
    data: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: float = ...,
        ) -> None: ...


class Float32MultiArray(Message, type_name="std_msgs/msg/Float32MultiArray"):
    """std_msgs/msg/Float32MultiArray: This was originally provided as an example message."""

    __slots__ = (
        "layout",
        "data",
    )
    layout: MultiArrayLayout
    data: FloatArray

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            layout: MultiArrayLayout = ...,
            data: Sequence[float] | npt.NDArray[Any] = ...,
        ) -> None: ...


class Float64(Message, type_name="std_msgs/msg/Float64"):
    """std_msgs/msg/Float64: This was originally provided as an example message."""

    __slots__ = ("data",)
    data: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: float = ...,
        ) -> None: ...


class Float64MultiArray(Message, type_name="std_msgs/msg/Float64MultiArray"):
    """std_msgs/msg/Float64MultiArray: This was originally provided as an example message."""

    __slots__ = (
        "layout",
        "data",
    )
    layout: MultiArrayLayout
    data: FloatArray

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            layout: MultiArrayLayout = ...,
            data: Sequence[float] | npt.NDArray[Any] = ...,
        ) -> None: ...


class Header(Message, type_name="std_msgs/msg/Header"):
    """std_msgs/msg/Header: Standard metadata for higher-level stamped data types."""

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
    """std_msgs/msg/Int16: This was originally provided as an example message."""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


class Int16MultiArray(Message, type_name="std_msgs/msg/Int16MultiArray"):
    """std_msgs/msg/Int16MultiArray: This was originally provided as an example message."""

    __slots__ = (
        "layout",
        "data",
    )
    layout: MultiArrayLayout
    data: IntArray

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            layout: MultiArrayLayout = ...,
            data: Sequence[int] | npt.NDArray[Any] = ...,
        ) -> None: ...


class Int32(Message, type_name="std_msgs/msg/Int32"):
    """std_msgs/msg/Int32: This was originally provided as an example message."""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


class Int32MultiArray(Message, type_name="std_msgs/msg/Int32MultiArray"):
    """std_msgs/msg/Int32MultiArray: This was originally provided as an example message."""

    __slots__ = (
        "layout",
        "data",
    )
    layout: MultiArrayLayout
    data: IntArray

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            layout: MultiArrayLayout = ...,
            data: Sequence[int] | npt.NDArray[Any] = ...,
        ) -> None: ...


class Int64(Message, type_name="std_msgs/msg/Int64"):
    """std_msgs/msg/Int64: This was originally provided as an example message."""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


class Int64MultiArray(Message, type_name="std_msgs/msg/Int64MultiArray"):
    """std_msgs/msg/Int64MultiArray: This was originally provided as an example message."""

    __slots__ = (
        "layout",
        "data",
    )
    layout: MultiArrayLayout
    data: IntArray

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            layout: MultiArrayLayout = ...,
            data: Sequence[int] | npt.NDArray[Any] = ...,
        ) -> None: ...


class Int8(Message, type_name="std_msgs/msg/Int8"):
    """std_msgs/msg/Int8: This was originally provided as an example message."""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


class Int8MultiArray(Message, type_name="std_msgs/msg/Int8MultiArray"):
    """std_msgs/msg/Int8MultiArray: This was originally provided as an example message."""

    __slots__ = (
        "layout",
        "data",
    )
    layout: MultiArrayLayout
    data: IntArray

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            layout: MultiArrayLayout = ...,
            data: Sequence[int] | npt.NDArray[Any] = ...,
        ) -> None: ...


class String(Message, type_name="std_msgs/msg/String"):
    """std_msgs/msg/String: This was originally provided as an example message."""

    __slots__ = ("data",)
    data: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: str = ...,
        ) -> None: ...


class UInt16(Message, type_name="std_msgs/msg/UInt16"):
    """std_msgs/msg/UInt16: This was originally provided as an example message."""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


class UInt16MultiArray(Message, type_name="std_msgs/msg/UInt16MultiArray"):
    """std_msgs/msg/UInt16MultiArray: This was originally provided as an example message."""

    __slots__ = (
        "layout",
        "data",
    )
    layout: MultiArrayLayout
    data: IntArray

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            layout: MultiArrayLayout = ...,
            data: Sequence[int] | npt.NDArray[Any] = ...,
        ) -> None: ...


class UInt32(Message, type_name="std_msgs/msg/UInt32"):
    """std_msgs/msg/UInt32: This was originally provided as an example message."""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


class UInt32MultiArray(Message, type_name="std_msgs/msg/UInt32MultiArray"):
    """std_msgs/msg/UInt32MultiArray: This was originally provided as an example message."""

    __slots__ = (
        "layout",
        "data",
    )
    layout: MultiArrayLayout
    data: IntArray

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            layout: MultiArrayLayout = ...,
            data: Sequence[int] | npt.NDArray[Any] = ...,
        ) -> None: ...


class UInt64(Message, type_name="std_msgs/msg/UInt64"):
    """std_msgs/msg/UInt64: This was originally provided as an example message."""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


class UInt64MultiArray(Message, type_name="std_msgs/msg/UInt64MultiArray"):
    """std_msgs/msg/UInt64MultiArray: This was originally provided as an example message."""

    __slots__ = (
        "layout",
        "data",
    )
    layout: MultiArrayLayout
    data: IntArray

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            layout: MultiArrayLayout = ...,
            data: Sequence[int] | npt.NDArray[Any] = ...,
        ) -> None: ...


class UInt8(Message, type_name="std_msgs/msg/UInt8"):
    """std_msgs/msg/UInt8: This was originally provided as an example message."""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


class UInt8MultiArray(Message, type_name="std_msgs/msg/UInt8MultiArray"):
    """std_msgs/msg/UInt8MultiArray: This was originally provided as an example message."""

    __slots__ = (
        "layout",
        "data",
    )
    layout: MultiArrayLayout
    data: IntArray

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            layout: MultiArrayLayout = ...,
            data: Sequence[int] | npt.NDArray[Any] = ...,
        ) -> None: ...


__all__ = [
    "Bool",
    "Byte",
    "ByteMultiArray",
    "Char",
    "ColorRGBA",
    "Empty",
    "Float32",
    "Float32MultiArray",
    "Float64",
    "Float64MultiArray",
    "Header",
    "Int16",
    "Int16MultiArray",
    "Int32",
    "Int32MultiArray",
    "Int64",
    "Int64MultiArray",
    "Int8",
    "Int8MultiArray",
    "MultiArrayDimension",
    "MultiArrayLayout",
    "String",
    "UInt16",
    "UInt16MultiArray",
    "UInt32",
    "UInt32MultiArray",
    "UInt64",
    "UInt64MultiArray",
    "UInt8",
    "UInt8MultiArray",
]
