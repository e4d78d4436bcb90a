"""rcl_interfaces: generated from ROS 2's definitions (the wheels node_runtime/msgs/ros_packages.txt pins) by `python -m node_runtime.msgs.generate`; do not edit."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any, ClassVar

if TYPE_CHECKING:
    import numpy.typing as npt

from node_runtime.msgs._base import Message, Service
from node_runtime.msgs._field import FloatArray, IntArray
from node_runtime.msgs.generated.builtin_interfaces import Time


class FloatingPointRange(Message, type_name="rcl_interfaces/msg/FloatingPointRange"):
    """rcl_interfaces/msg/FloatingPointRange: Represents bounds and a step value for a floating point typed parameter."""

    __slots__ = (
        "from_value",
        "to_value",
        "step",
    )
    from_value: float
    to_value: float
    step: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            from_value: float = ...,
            to_value: float = ...,
            step: float = ...,
        ) -> None: ...


class IntegerRange(Message, type_name="rcl_interfaces/msg/IntegerRange"):
    """rcl_interfaces/msg/IntegerRange: Represents bounds and a step value for an integer typed parameter."""

    __slots__ = (
        "from_value",
        "to_value",
        "step",
    )
    from_value: int
    to_value: int
    step: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            from_value: int = ...,
            to_value: int = ...,
            step: int = ...,
        ) -> None: ...


class ListParametersResult(Message, type_name="rcl_interfaces/msg/ListParametersResult"):
    """rcl_interfaces/msg/ListParametersResult: The resulting parameters under the given prefixes."""

    __slots__ = (
        "names",
        "prefixes",
    )
    names: list[str]
    prefixes: list[str]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            names: Sequence[str] = ...,
            prefixes: Sequence[str] = ...,
        ) -> None: ...


class Log(Message, type_name="rcl_interfaces/msg/Log"):
    """rcl_interfaces/msg/Log"""

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


class LoggerLevel(Message, type_name="rcl_interfaces/msg/LoggerLevel"):
    """rcl_interfaces/msg/LoggerLevel: All available logger levels; these correspond to the enum in rcutils/logger.h"""

    __slots__ = (
        "name",
        "level",
    )
    LOG_LEVEL_UNKNOWN: ClassVar[int]
    LOG_LEVEL_DEBUG: ClassVar[int]
    LOG_LEVEL_INFO: ClassVar[int]
    LOG_LEVEL_WARN: ClassVar[int]
    LOG_LEVEL_ERROR: ClassVar[int]
    LOG_LEVEL_FATAL: ClassVar[int]
    name: str
    level: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            name: str = ...,
            level: int = ...,
        ) -> None: ...


class ParameterValue(Message, type_name="rcl_interfaces/msg/ParameterValue"):
    """rcl_interfaces/msg/ParameterValue: Used to determine which of the next *_value fields are set."""

    __slots__ = (
        "type",
        "bool_value",
        "integer_value",
        "double_value",
        "string_value",
        "byte_array_value",
        "bool_array_value",
        "integer_array_value",
        "double_array_value",
        "string_array_value",
    )
    type: int
    bool_value: bool
    integer_value: int
    double_value: float
    string_value: str
    byte_array_value: IntArray
    bool_array_value: list[bool]
    integer_array_value: IntArray
    double_array_value: FloatArray
    string_array_value: list[str]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            type: int = ...,
            bool_value: bool = ...,
            integer_value: int = ...,
            double_value: float = ...,
            string_value: str = ...,
            byte_array_value: Sequence[int] | npt.NDArray[Any] = ...,
            bool_array_value: Sequence[bool] | npt.NDArray[Any] = ...,
            integer_array_value: Sequence[int] | npt.NDArray[Any] = ...,
            double_array_value: Sequence[float] | npt.NDArray[Any] = ...,
            string_array_value: Sequence[str] = ...,
        ) -> None: ...


class Parameter(Message, type_name="rcl_interfaces/msg/Parameter"):
    """rcl_interfaces/msg/Parameter: This is the message to communicate a parameter. It is an open struct with an enum in"""

    __slots__ = (
        "name",
        "value",
    )
    name: str
    value: ParameterValue

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            name: str = ...,
            value: ParameterValue = ...,
        ) -> None: ...


class ParameterDescriptor(Message, type_name="rcl_interfaces/msg/ParameterDescriptor"):
    """rcl_interfaces/msg/ParameterDescriptor: This is the message to communicate a parameter's descriptor."""

    __slots__ = (
        "name",
        "type",
        "description",
        "additional_constraints",
        "read_only",
        "dynamic_typing",
        "floating_point_range",
        "integer_range",
    )
    name: str
    type: int
    description: str
    additional_constraints: str
    read_only: bool
    dynamic_typing: bool
    floating_point_range: list[FloatingPointRange]
    integer_range: list[IntegerRange]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            name: str = ...,
            type: int = ...,
            description: str = ...,
            additional_constraints: str = ...,
            read_only: bool = ...,
            dynamic_typing: bool = ...,
            floating_point_range: Sequence[FloatingPointRange] = ...,
            integer_range: Sequence[IntegerRange] = ...,
        ) -> None: ...


class ParameterEvent(Message, type_name="rcl_interfaces/msg/ParameterEvent"):
    """rcl_interfaces/msg/ParameterEvent: This message contains a parameter event."""

    __slots__ = (
        "stamp",
        "node",
        "new_parameters",
        "changed_parameters",
        "deleted_parameters",
    )
    stamp: Time
    node: str
    new_parameters: list[Parameter]
    changed_parameters: list[Parameter]
    deleted_parameters: list[Parameter]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            stamp: Time = ...,
            node: str = ...,
            new_parameters: Sequence[Parameter] = ...,
            changed_parameters: Sequence[Parameter] = ...,
            deleted_parameters: Sequence[Parameter] = ...,
        ) -> None: ...


class ParameterEventDescriptors(Message, type_name="rcl_interfaces/msg/ParameterEventDescriptors"):
    """rcl_interfaces/msg/ParameterEventDescriptors: This message contains descriptors of a parameter event."""

    __slots__ = (
        "new_parameters",
        "changed_parameters",
        "deleted_parameters",
    )
    new_parameters: list[ParameterDescriptor]
    changed_parameters: list[ParameterDescriptor]
    deleted_parameters: list[ParameterDescriptor]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            new_parameters: Sequence[ParameterDescriptor] = ...,
            changed_parameters: Sequence[ParameterDescriptor] = ...,
            deleted_parameters: Sequence[ParameterDescriptor] = ...,
        ) -> None: ...


class ParameterType(Message, type_name="rcl_interfaces/msg/ParameterType"):
    """rcl_interfaces/msg/ParameterType: These types correspond to the value that is set in the ParameterValue message."""

    __slots__ = ()
    PARAMETER_NOT_SET: ClassVar[int]
    PARAMETER_BOOL: ClassVar[int]
    PARAMETER_INTEGER: ClassVar[int]
    PARAMETER_DOUBLE: ClassVar[int]
    PARAMETER_STRING: ClassVar[int]
    PARAMETER_BYTE_ARRAY: ClassVar[int]
    PARAMETER_BOOL_ARRAY: ClassVar[int]
    PARAMETER_INTEGER_ARRAY: ClassVar[int]
    PARAMETER_DOUBLE_ARRAY: ClassVar[int]
    PARAMETER_STRING_ARRAY: ClassVar[int]


class SetLoggerLevelsResult(Message, type_name="rcl_interfaces/msg/SetLoggerLevelsResult"):
    """rcl_interfaces/msg/SetLoggerLevelsResult: True when succeed, false when failed."""

    __slots__ = (
        "successful",
        "reason",
    )
    successful: bool
    reason: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            successful: bool = ...,
            reason: str = ...,
        ) -> None: ...


class SetParametersResult(Message, type_name="rcl_interfaces/msg/SetParametersResult"):
    """rcl_interfaces/msg/SetParametersResult: A true value of the same index indicates that the parameter was set"""

    __slots__ = (
        "successful",
        "reason",
    )
    successful: bool
    reason: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            successful: bool = ...,
            reason: str = ...,
        ) -> None: ...


class DescribeParameters_Request(Message, type_name="rcl_interfaces/srv/DescribeParameters_Request"):
    """rcl_interfaces/srv/DescribeParameters_Request: A list of parameters of which to get the descriptor."""

    __slots__ = ("names",)
    names: list[str]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            names: Sequence[str] = ...,
        ) -> None: ...


class DescribeParameters_Response(Message, type_name="rcl_interfaces/srv/DescribeParameters_Response"):
    """rcl_interfaces/srv/DescribeParameters_Response: A list of the descriptors of all parameters requested in the same order"""

    __slots__ = ("descriptors",)
    descriptors: list[ParameterDescriptor]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            descriptors: Sequence[ParameterDescriptor] = ...,
        ) -> None: ...


class GetLoggerLevels_Request(Message, type_name="rcl_interfaces/srv/GetLoggerLevels_Request"):
    """rcl_interfaces/srv/GetLoggerLevels_Request: A list of logger names to get."""

    __slots__ = ("names",)
    names: list[str]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            names: Sequence[str] = ...,
        ) -> None: ...


class GetLoggerLevels_Response(Message, type_name="rcl_interfaces/srv/GetLoggerLevels_Response"):
    """rcl_interfaces/srv/GetLoggerLevels_Response: List of logger levels which is the same order as the provided names. If a"""

    __slots__ = ("levels",)
    levels: list[LoggerLevel]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            levels: Sequence[LoggerLevel] = ...,
        ) -> None: ...


class GetParameterTypes_Request(Message, type_name="rcl_interfaces/srv/GetParameterTypes_Request"):
    """rcl_interfaces/srv/GetParameterTypes_Request: A list of parameter names."""

    __slots__ = ("names",)
    names: list[str]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            names: Sequence[str] = ...,
        ) -> None: ...


class GetParameterTypes_Response(Message, type_name="rcl_interfaces/srv/GetParameterTypes_Response"):
    """rcl_interfaces/srv/GetParameterTypes_Response: List of types which is the same length and order as the provided names."""

    __slots__ = ("types",)
    types: IntArray

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            types: Sequence[int] | npt.NDArray[Any] = ...,
        ) -> None: ...


class GetParameters_Request(Message, type_name="rcl_interfaces/srv/GetParameters_Request"):
    """rcl_interfaces/srv/GetParameters_Request: TODO(wjwwood): Decide on the rules for grouping, nodes, and parameter 'names'"""

    __slots__ = ("names",)
    names: list[str]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            names: Sequence[str] = ...,
        ) -> None: ...


class GetParameters_Response(Message, type_name="rcl_interfaces/srv/GetParameters_Response"):
    """rcl_interfaces/srv/GetParameters_Response: List of values which is the same length and order as the provided names. If a"""

    __slots__ = ("values",)
    values: list[ParameterValue]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            values: Sequence[ParameterValue] = ...,
        ) -> None: ...


class ListParameters_Request(Message, type_name="rcl_interfaces/srv/ListParameters_Request"):
    """rcl_interfaces/srv/ListParameters_Request: Recursively get parameters with unlimited depth."""

    __slots__ = (
        "prefixes",
        "depth",
    )
    DEPTH_RECURSIVE: ClassVar[int]
    prefixes: list[str]
    depth: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            prefixes: Sequence[str] = ...,
            depth: int = ...,
        ) -> None: ...


class ListParameters_Response(Message, type_name="rcl_interfaces/srv/ListParameters_Response"):
    """rcl_interfaces/srv/ListParameters_Response: The list of parameter names and their prefixes."""

    __slots__ = ("result",)
    result: ListParametersResult

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            result: ListParametersResult = ...,
        ) -> None: ...


class SetLoggerLevels_Request(Message, type_name="rcl_interfaces/srv/SetLoggerLevels_Request"):
    """rcl_interfaces/srv/SetLoggerLevels_Request: A list of loggers to set."""

    __slots__ = ("levels",)
    levels: list[LoggerLevel]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            levels: Sequence[LoggerLevel] = ...,
        ) -> None: ...


class SetLoggerLevels_Response(Message, type_name="rcl_interfaces/srv/SetLoggerLevels_Response"):
    """rcl_interfaces/srv/SetLoggerLevels_Response: Indicates whether setting each logger succeeded or not and why."""

    __slots__ = ("results",)
    results: list[SetLoggerLevelsResult]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            results: Sequence[SetLoggerLevelsResult] = ...,
        ) -> None: ...


class SetParameters_Request(Message, type_name="rcl_interfaces/srv/SetParameters_Request"):
    """rcl_interfaces/srv/SetParameters_Request: A list of parameters to set."""

    __slots__ = ("parameters",)
    parameters: list[Parameter]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            parameters: Sequence[Parameter] = ...,
        ) -> None: ...


class SetParameters_Response(Message, type_name="rcl_interfaces/srv/SetParameters_Response"):
    """rcl_interfaces/srv/SetParameters_Response: Indicates whether setting each parameter succeeded or not and why."""

    __slots__ = ("results",)
    results: list[SetParametersResult]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            results: Sequence[SetParametersResult] = ...,
        ) -> None: ...


class SetParametersAtomically_Request(
    Message, type_name="rcl_interfaces/srv/SetParametersAtomically_Request"
):
    """rcl_interfaces/srv/SetParametersAtomically_Request: A list of parameters to set atomically."""

    __slots__ = ("parameters",)
    parameters: list[Parameter]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            parameters: Sequence[Parameter] = ...,
        ) -> None: ...


class SetParametersAtomically_Response(
    Message, type_name="rcl_interfaces/srv/SetParametersAtomically_Response"
):
    """rcl_interfaces/srv/SetParametersAtomically_Response: Indicates whether setting all of the parameters succeeded or not and why."""

    __slots__ = ("result",)
    result: SetParametersResult

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            result: SetParametersResult = ...,
        ) -> None: ...


class DescribeParameters(Service, type_name="rcl_interfaces/srv/DescribeParameters"):
    """rcl_interfaces/srv/DescribeParameters: call with a DescribeParameters.Request, answered with a DescribeParameters.Response."""

    Request = DescribeParameters_Request
    Response = DescribeParameters_Response


class GetLoggerLevels(Service, type_name="rcl_interfaces/srv/GetLoggerLevels"):
    """rcl_interfaces/srv/GetLoggerLevels: call with a GetLoggerLevels.Request, answered with a GetLoggerLevels.Response."""

    Request = GetLoggerLevels_Request
    Response = GetLoggerLevels_Response


class GetParameterTypes(Service, type_name="rcl_interfaces/srv/GetParameterTypes"):
    """rcl_interfaces/srv/GetParameterTypes: call with a GetParameterTypes.Request, answered with a GetParameterTypes.Response."""

    Request = GetParameterTypes_Request
    Response = GetParameterTypes_Response


class GetParameters(Service, type_name="rcl_interfaces/srv/GetParameters"):
    """rcl_interfaces/srv/GetParameters: call with a GetParameters.Request, answered with a GetParameters.Response."""

    Request = GetParameters_Request
    Response = GetParameters_Response


class ListParameters(Service, type_name="rcl_interfaces/srv/ListParameters"):
    """rcl_interfaces/srv/ListParameters: call with a ListParameters.Request, answered with a ListParameters.Response."""

    Request = ListParameters_Request
    Response = ListParameters_Response


class SetLoggerLevels(Service, type_name="rcl_interfaces/srv/SetLoggerLevels"):
    """rcl_interfaces/srv/SetLoggerLevels: call with a SetLoggerLevels.Request, answered with a SetLoggerLevels.Response."""

    Request = SetLoggerLevels_Request
    Response = SetLoggerLevels_Response


class SetParameters(Service, type_name="rcl_interfaces/srv/SetParameters"):
    """rcl_interfaces/srv/SetParameters: call with a SetParameters.Request, answered with a SetParameters.Response."""

    Request = SetParameters_Request
    Response = SetParameters_Response


class SetParametersAtomically(Service, type_name="rcl_interfaces/srv/SetParametersAtomically"):
    """rcl_interfaces/srv/SetParametersAtomically: call with a SetParametersAtomically.Request, answered with a SetParametersAtomically.Response."""

    Request = SetParametersAtomically_Request
    Response = SetParametersAtomically_Response


__all__ = [
    "DescribeParameters",
    "DescribeParameters_Request",
    "DescribeParameters_Response",
    "FloatingPointRange",
    "GetLoggerLevels",
    "GetLoggerLevels_Request",
    "GetLoggerLevels_Response",
    "GetParameterTypes",
    "GetParameterTypes_Request",
    "GetParameterTypes_Response",
    "GetParameters",
    "GetParameters_Request",
    "GetParameters_Response",
    "IntegerRange",
    "ListParameters",
    "ListParametersResult",
    "ListParameters_Request",
    "ListParameters_Response",
    "Log",
    "LoggerLevel",
    "Parameter",
    "ParameterDescriptor",
    "ParameterEvent",
    "ParameterEventDescriptors",
    "ParameterType",
    "ParameterValue",
    "SetLoggerLevels",
    "SetLoggerLevelsResult",
    "SetLoggerLevels_Request",
    "SetLoggerLevels_Response",
    "SetParameters",
    "SetParametersAtomically",
    "SetParametersAtomically_Request",
    "SetParametersAtomically_Response",
    "SetParametersResult",
    "SetParameters_Request",
    "SetParameters_Response",
]
