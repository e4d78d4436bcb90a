"""example_interfaces: generated from node_runtime/msgs/interfaces/example_interfaces by `python -m node_runtime.msgs.generate`; do not edit."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import numpy.typing as npt

from node_runtime.msgs._action import Action
from node_runtime.msgs._base import Message, Service
from node_runtime.msgs._field import FloatArray, IntArray
from node_runtime.msgs.generated.action_msgs import CancelGoal, GoalStatusArray
from node_runtime.msgs.generated.builtin_interfaces import Time
from node_runtime.msgs.generated.unique_identifier_msgs import UUID


class Bool(Message, type_name="example_interfaces/msg/Bool"):
    """example_interfaces/msg/Bool: One bool value, as the examples publish it."""

    __slots__ = ("data",)
    data: bool

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: bool = ...,
        ) -> None: ...


class Byte(Message, type_name="example_interfaces/msg/Byte"):
    """example_interfaces/msg/Byte: One byte value, as the examples publish it."""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


class MultiArrayDimension(Message, type_name="example_interfaces/msg/MultiArrayDimension"):
    """example_interfaces/msg/MultiArrayDimension: One dimension of a multi-dimensional array: its name, length and stride."""

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


class MultiArrayLayout(Message, type_name="example_interfaces/msg/MultiArrayLayout"):
    """example_interfaces/msg/MultiArrayLayout: How a multi-dimensional array lies in its flat data."""

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


class ByteMultiArray(Message, type_name="example_interfaces/msg/ByteMultiArray"):
    """example_interfaces/msg/ByteMultiArray: A multi-dimensional array of byte, flat, with its layout."""

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


class Char(Message, type_name="example_interfaces/msg/Char"):
    """example_interfaces/msg/Char: One char value, as the examples publish it."""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


class Empty(Message, type_name="example_interfaces/msg/Empty"):
    """example_interfaces/msg/Empty: A message without fields."""

    __slots__ = ()


class Float32(Message, type_name="example_interfaces/msg/Float32"):
    """example_interfaces/msg/Float32: One float32 value, as the examples publish it."""

    __slots__ = ("data",)
    data: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: float = ...,
        ) -> None: ...


class Float32MultiArray(Message, type_name="example_interfaces/msg/Float32MultiArray"):
    """example_interfaces/msg/Float32MultiArray: A multi-dimensional array of float32, flat, with its layout."""

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


class Float64(Message, type_name="example_interfaces/msg/Float64"):
    """example_interfaces/msg/Float64: One float64 value, as the examples publish it."""

    __slots__ = ("data",)
    data: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: float = ...,
        ) -> None: ...


class Float64MultiArray(Message, type_name="example_interfaces/msg/Float64MultiArray"):
    """example_interfaces/msg/Float64MultiArray: A multi-dimensional array of float64, flat, with its layout."""

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


class Int16(Message, type_name="example_interfaces/msg/Int16"):
    """example_interfaces/msg/Int16: One int16 value, as the examples publish it."""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


class Int16MultiArray(Message, type_name="example_interfaces/msg/Int16MultiArray"):
    """example_interfaces/msg/Int16MultiArray: A multi-dimensional array of int16, flat, with its layout."""

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


class Int32(Message, type_name="example_interfaces/msg/Int32"):
    """example_interfaces/msg/Int32: One int32 value, as the examples publish it."""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


class Int32MultiArray(Message, type_name="example_interfaces/msg/Int32MultiArray"):
    """example_interfaces/msg/Int32MultiArray: A multi-dimensional array of int32, flat, with its layout."""

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


class Int64(Message, type_name="example_interfaces/msg/Int64"):
    """example_interfaces/msg/Int64: One int64 value, as the examples publish it."""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


class Int64MultiArray(Message, type_name="example_interfaces/msg/Int64MultiArray"):
    """example_interfaces/msg/Int64MultiArray: A multi-dimensional array of int64, flat, with its layout."""

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


class Int8(Message, type_name="example_interfaces/msg/Int8"):
    """example_interfaces/msg/Int8: One int8 value, as the examples publish it."""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


class Int8MultiArray(Message, type_name="example_interfaces/msg/Int8MultiArray"):
    """example_interfaces/msg/Int8MultiArray: A multi-dimensional array of int8, flat, with its layout."""

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


class String(Message, type_name="example_interfaces/msg/String"):
    """example_interfaces/msg/String: One string value, as the examples publish it."""

    __slots__ = ("data",)
    data: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: str = ...,
        ) -> None: ...


class UInt16(Message, type_name="example_interfaces/msg/UInt16"):
    """example_interfaces/msg/UInt16: One uint16 value, as the examples publish it."""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


class UInt16MultiArray(Message, type_name="example_interfaces/msg/UInt16MultiArray"):
    """example_interfaces/msg/UInt16MultiArray: A multi-dimensional array of uint16, flat, with its layout."""

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


class UInt32(Message, type_name="example_interfaces/msg/UInt32"):
    """example_interfaces/msg/UInt32: One uint32 value, as the examples publish it."""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


class UInt32MultiArray(Message, type_name="example_interfaces/msg/UInt32MultiArray"):
    """example_interfaces/msg/UInt32MultiArray: A multi-dimensional array of uint32, flat, with its layout."""

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


class UInt64(Message, type_name="example_interfaces/msg/UInt64"):
    """example_interfaces/msg/UInt64: One uint64 value, as the examples publish it."""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


class UInt64MultiArray(Message, type_name="example_interfaces/msg/UInt64MultiArray"):
    """example_interfaces/msg/UInt64MultiArray: A multi-dimensional array of uint64, flat, with its layout."""

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


class UInt8(Message, type_name="example_interfaces/msg/UInt8"):
    """example_interfaces/msg/UInt8: One uint8 value, as the examples publish it."""

    __slots__ = ("data",)
    data: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: int = ...,
        ) -> None: ...


class UInt8MultiArray(Message, type_name="example_interfaces/msg/UInt8MultiArray"):
    """example_interfaces/msg/UInt8MultiArray: A multi-dimensional array of uint8, flat, with its layout."""

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


class Fibonacci_Goal(Message, type_name="example_interfaces/action/Fibonacci_Goal"):
    """example_interfaces/action/Fibonacci_Goal"""

    __slots__ = ("order",)
    order: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            order: int = ...,
        ) -> None: ...


class Fibonacci_Result(Message, type_name="example_interfaces/action/Fibonacci_Result"):
    """example_interfaces/action/Fibonacci_Result"""

    __slots__ = ("sequence",)
    sequence: IntArray

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            sequence: Sequence[int] | npt.NDArray[Any] = ...,
        ) -> None: ...


class Fibonacci_Feedback(Message, type_name="example_interfaces/action/Fibonacci_Feedback"):
    """example_interfaces/action/Fibonacci_Feedback"""

    __slots__ = ("sequence",)
    sequence: IntArray

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            sequence: Sequence[int] | npt.NDArray[Any] = ...,
        ) -> None: ...


class Fibonacci_FeedbackMessage(Message, type_name="example_interfaces/action/Fibonacci_FeedbackMessage"):
    """example_interfaces/action/Fibonacci_FeedbackMessage"""

    __slots__ = (
        "goal_id",
        "feedback",
    )
    goal_id: UUID
    feedback: Fibonacci_Feedback

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            goal_id: UUID = ...,
            feedback: Fibonacci_Feedback = ...,
        ) -> None: ...


class AddTwoInts_Request(Message, type_name="example_interfaces/srv/AddTwoInts_Request"):
    """example_interfaces/srv/AddTwoInts_Request"""

    __slots__ = (
        "a",
        "b",
    )
    a: int
    b: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            a: int = ...,
            b: int = ...,
        ) -> None: ...


class AddTwoInts_Response(Message, type_name="example_interfaces/srv/AddTwoInts_Response"):
    """example_interfaces/srv/AddTwoInts_Response"""

    __slots__ = ("sum",)
    sum: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            sum: int = ...,
        ) -> None: ...


class SetBool_Request(Message, type_name="example_interfaces/srv/SetBool_Request"):
    """example_interfaces/srv/SetBool_Request: Set a flag: the answer says whether it took and why not."""

    __slots__ = ("data",)
    data: bool

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: bool = ...,
        ) -> None: ...


class SetBool_Response(Message, type_name="example_interfaces/srv/SetBool_Response"):
    """example_interfaces/srv/SetBool_Response"""

    __slots__ = (
        "success",
        "message",
    )
    success: bool
    message: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            success: bool = ...,
            message: str = ...,
        ) -> None: ...


class Trigger_Request(Message, type_name="example_interfaces/srv/Trigger_Request"):
    """example_interfaces/srv/Trigger_Request: Start something: the answer says whether it ran and why not."""

    __slots__ = ()


class Trigger_Response(Message, type_name="example_interfaces/srv/Trigger_Response"):
    """example_interfaces/srv/Trigger_Response"""

    __slots__ = (
        "success",
        "message",
    )
    success: bool
    message: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            success: bool = ...,
            message: str = ...,
        ) -> None: ...


class Fibonacci_SendGoal_Request(Message, type_name="example_interfaces/action/Fibonacci_SendGoal_Request"):
    """example_interfaces/action/Fibonacci_SendGoal_Request"""

    __slots__ = (
        "goal_id",
        "goal",
    )
    goal_id: UUID
    goal: Fibonacci_Goal

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            goal_id: UUID = ...,
            goal: Fibonacci_Goal = ...,
        ) -> None: ...


class Fibonacci_SendGoal_Response(Message, type_name="example_interfaces/action/Fibonacci_SendGoal_Response"):
    """example_interfaces/action/Fibonacci_SendGoal_Response"""

    __slots__ = (
        "accepted",
        "stamp",
    )
    accepted: bool
    stamp: Time

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            accepted: bool = ...,
            stamp: Time = ...,
        ) -> None: ...


class Fibonacci_GetResult_Request(Message, type_name="example_interfaces/action/Fibonacci_GetResult_Request"):
    """example_interfaces/action/Fibonacci_GetResult_Request"""

    __slots__ = ("goal_id",)
    goal_id: UUID

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            goal_id: UUID = ...,
        ) -> None: ...


class Fibonacci_GetResult_Response(
    Message, type_name="example_interfaces/action/Fibonacci_GetResult_Response"
):
    """example_interfaces/action/Fibonacci_GetResult_Response"""

    __slots__ = (
        "status",
        "result",
    )
    status: int
    result: Fibonacci_Result

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            status: int = ...,
            result: Fibonacci_Result = ...,
        ) -> None: ...


class AddTwoInts(Service, type_name="example_interfaces/srv/AddTwoInts"):
    """example_interfaces/srv/AddTwoInts: call with a AddTwoInts.Request, answered with a AddTwoInts.Response."""

    Request = AddTwoInts_Request
    Response = AddTwoInts_Response


class SetBool(Service, type_name="example_interfaces/srv/SetBool"):
    """example_interfaces/srv/SetBool: call with a SetBool.Request, answered with a SetBool.Response."""

    Request = SetBool_Request
    Response = SetBool_Response


class Trigger(Service, type_name="example_interfaces/srv/Trigger"):
    """example_interfaces/srv/Trigger: call with a Trigger.Request, answered with a Trigger.Response."""

    Request = Trigger_Request
    Response = Trigger_Response


class Fibonacci_SendGoal(Service, type_name="example_interfaces/action/Fibonacci_SendGoal"):
    """example_interfaces/action/Fibonacci_SendGoal: call with a Fibonacci_SendGoal.Request, answered with a Fibonacci_SendGoal.Response."""

    Request = Fibonacci_SendGoal_Request
    Response = Fibonacci_SendGoal_Response


class Fibonacci_GetResult(Service, type_name="example_interfaces/action/Fibonacci_GetResult"):
    """example_interfaces/action/Fibonacci_GetResult: call with a Fibonacci_GetResult.Request, answered with a Fibonacci_GetResult.Response."""

    Request = Fibonacci_GetResult_Request
    Response = Fibonacci_GetResult_Response


class Fibonacci(Action, type_name="example_interfaces/action/Fibonacci"):
    """example_interfaces/action/Fibonacci: a Fibonacci.Goal, answered with a Fibonacci.Result, Fibonacci.Feedback meanwhile."""

    Goal = Fibonacci_Goal
    Result = Fibonacci_Result
    Feedback = Fibonacci_Feedback

    class Impl:
        SendGoalService = Fibonacci_SendGoal
        GetResultService = Fibonacci_GetResult
        FeedbackMessage = Fibonacci_FeedbackMessage
        CancelGoalService = CancelGoal
        GoalStatusMessage = GoalStatusArray


__all__ = [
    "AddTwoInts",
    "AddTwoInts_Request",
    "AddTwoInts_Response",
    "Bool",
    "Byte",
    "ByteMultiArray",
    "Char",
    "Empty",
    "Fibonacci",
    "Fibonacci_Feedback",
    "Fibonacci_FeedbackMessage",
    "Fibonacci_GetResult",
    "Fibonacci_GetResult_Request",
    "Fibonacci_GetResult_Response",
    "Fibonacci_Goal",
    "Fibonacci_Result",
    "Fibonacci_SendGoal",
    "Fibonacci_SendGoal_Request",
    "Fibonacci_SendGoal_Response",
    "Float32",
    "Float32MultiArray",
    "Float64",
    "Float64MultiArray",
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
    "SetBool",
    "SetBool_Request",
    "SetBool_Response",
    "String",
    "Trigger",
    "Trigger_Request",
    "Trigger_Response",
    "UInt16",
    "UInt16MultiArray",
    "UInt32",
    "UInt32MultiArray",
    "UInt64",
    "UInt64MultiArray",
    "UInt8",
    "UInt8MultiArray",
]
