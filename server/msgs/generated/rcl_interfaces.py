"""rcl_interfaces: generated from server/msgs/interfaces/rcl_interfaces by `python -m server.msgs.generate`; do not edit."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any, ClassVar

if TYPE_CHECKING:
    import numpy.typing as npt

from .._base import Message, Service
from .._field import FloatArray, IntArray
from .builtin_interfaces import Time


class FloatingPointRange(Message, type_name="rcl_interfaces/msg/FloatingPointRange"):
    """rcl_interfaces/msg/FloatingPointRange: Bounds (inclusive) and a step for a floating point parameter; step 0 means any value."""

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
    """rcl_interfaces/msg/IntegerRange: Bounds (inclusive) and a step for an integer parameter; step 0 means any value."""

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
    """rcl_interfaces/msg/ListParametersResult: Parameter names and the prefixes they sit under."""

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


class ParameterValue(Message, type_name="rcl_interfaces/msg/ParameterValue"):
    """rcl_interfaces/msg/ParameterValue: A parameter value: type (a ParameterType constant) says which field holds it."""

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
    """rcl_interfaces/msg/Parameter: A named parameter value."""

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
    """rcl_interfaces/msg/ParameterDescriptor: A parameter's description and constraints (a range, read-only) for tools and checks."""

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
    """rcl_interfaces/msg/ParameterEvent: What changed in one node's parameters, as published on /parameter_events."""

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


class ParameterType(Message, type_name="rcl_interfaces/msg/ParameterType"):
    """rcl_interfaces/msg/ParameterType: What a parameter value may hold: the type tags of ParameterValue.type."""

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


class SetParametersResult(Message, type_name="rcl_interfaces/msg/SetParametersResult"):
    """rcl_interfaces/msg/SetParametersResult: Whether setting a parameter succeeded, and why not (for logs and tools)."""

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
    """rcl_interfaces/srv/DescribeParameters_Request: Descriptors of the named parameters."""

    __slots__ = ("names",)
    names: list[str]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            names: Sequence[str] = ...,
        ) -> None: ...


class DescribeParameters_Response(Message, type_name="rcl_interfaces/srv/DescribeParameters_Response"):
    """rcl_interfaces/srv/DescribeParameters_Response"""

    __slots__ = ("descriptors",)
    descriptors: list[ParameterDescriptor]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            descriptors: Sequence[ParameterDescriptor] = ...,
        ) -> None: ...


class GetParameterTypes_Request(Message, type_name="rcl_interfaces/srv/GetParameterTypes_Request"):
    """rcl_interfaces/srv/GetParameterTypes_Request: Types (ParameterType constants) of the named parameters."""

    __slots__ = ("names",)
    names: list[str]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            names: Sequence[str] = ...,
        ) -> None: ...


class GetParameterTypes_Response(Message, type_name="rcl_interfaces/srv/GetParameterTypes_Response"):
    """rcl_interfaces/srv/GetParameterTypes_Response"""

    __slots__ = ("types",)
    types: IntArray

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            types: Sequence[int] | npt.NDArray[Any] = ...,
        ) -> None: ...


class GetParameters_Request(Message, type_name="rcl_interfaces/srv/GetParameters_Request"):
    """rcl_interfaces/srv/GetParameters_Request: Values of the named parameters (type NOT_SET for an unknown name)."""

    __slots__ = ("names",)
    names: list[str]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            names: Sequence[str] = ...,
        ) -> None: ...


class GetParameters_Response(Message, type_name="rcl_interfaces/srv/GetParameters_Response"):
    """rcl_interfaces/srv/GetParameters_Response"""

    __slots__ = ("values",)
    values: list[ParameterValue]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            values: Sequence[ParameterValue] = ...,
        ) -> None: ...


class ListParameters_Request(Message, type_name="rcl_interfaces/srv/ListParameters_Request"):
    """rcl_interfaces/srv/ListParameters_Request: Parameters under the prefixes, down to depth separators (0: all)."""

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
    """rcl_interfaces/srv/ListParameters_Response"""

    __slots__ = ("result",)
    result: ListParametersResult

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            result: ListParametersResult = ...,
        ) -> None: ...


class SetParameters_Request(Message, type_name="rcl_interfaces/srv/SetParameters_Request"):
    """rcl_interfaces/srv/SetParameters_Request: Set each parameter on its own; one result per parameter."""

    __slots__ = ("parameters",)
    parameters: list[Parameter]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            parameters: Sequence[Parameter] = ...,
        ) -> None: ...


class SetParameters_Response(Message, type_name="rcl_interfaces/srv/SetParameters_Response"):
    """rcl_interfaces/srv/SetParameters_Response"""

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
    """rcl_interfaces/srv/SetParametersAtomically_Request: Set all the parameters or none."""

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
    """rcl_interfaces/srv/SetParametersAtomically_Response"""

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
    "Parameter",
    "ParameterDescriptor",
    "ParameterEvent",
    "ParameterType",
    "ParameterValue",
    "SetParameters",
    "SetParametersAtomically",
    "SetParametersAtomically_Request",
    "SetParametersAtomically_Response",
    "SetParametersResult",
    "SetParameters_Request",
    "SetParameters_Response",
]
