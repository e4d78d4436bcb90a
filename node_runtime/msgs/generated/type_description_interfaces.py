"""type_description_interfaces: generated from ROS 2's definitions (the wheels node_runtime/msgs/ros_packages.txt pins) by `python -m node_runtime.msgs.generate`; do not edit."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, ClassVar

from node_runtime.msgs._base import Message, Service


class FieldType(Message, type_name="type_description_interfaces/msg/FieldType"):
    """type_description_interfaces/msg/FieldType: Represents the type of a field and related meta-data."""

    __slots__ = (
        "type_id",
        "capacity",
        "string_capacity",
        "nested_type_name",
    )
    FIELD_TYPE_NOT_SET: ClassVar[int]
    FIELD_TYPE_NESTED_TYPE: ClassVar[int]
    FIELD_TYPE_INT8: ClassVar[int]
    FIELD_TYPE_UINT8: ClassVar[int]
    FIELD_TYPE_INT16: ClassVar[int]
    FIELD_TYPE_UINT16: ClassVar[int]
    FIELD_TYPE_INT32: ClassVar[int]
    FIELD_TYPE_UINT32: ClassVar[int]
    FIELD_TYPE_INT64: ClassVar[int]
    FIELD_TYPE_UINT64: ClassVar[int]
    FIELD_TYPE_FLOAT: ClassVar[int]
    FIELD_TYPE_DOUBLE: ClassVar[int]
    FIELD_TYPE_LONG_DOUBLE: ClassVar[int]
    FIELD_TYPE_CHAR: ClassVar[int]
    FIELD_TYPE_WCHAR: ClassVar[int]
    FIELD_TYPE_BOOLEAN: ClassVar[int]
    FIELD_TYPE_BYTE: ClassVar[int]
    FIELD_TYPE_STRING: ClassVar[int]
    FIELD_TYPE_WSTRING: ClassVar[int]
    FIELD_TYPE_FIXED_STRING: ClassVar[int]
    FIELD_TYPE_FIXED_WSTRING: ClassVar[int]
    FIELD_TYPE_BOUNDED_STRING: ClassVar[int]
    FIELD_TYPE_BOUNDED_WSTRING: ClassVar[int]
    FIELD_TYPE_NESTED_TYPE_ARRAY: ClassVar[int]
    FIELD_TYPE_INT8_ARRAY: ClassVar[int]
    FIELD_TYPE_UINT8_ARRAY: ClassVar[int]
    FIELD_TYPE_INT16_ARRAY: ClassVar[int]
    FIELD_TYPE_UINT16_ARRAY: ClassVar[int]
    FIELD_TYPE_INT32_ARRAY: ClassVar[int]
    FIELD_TYPE_UINT32_ARRAY: ClassVar[int]
    FIELD_TYPE_INT64_ARRAY: ClassVar[int]
    FIELD_TYPE_UINT64_ARRAY: ClassVar[int]
    FIELD_TYPE_FLOAT_ARRAY: ClassVar[int]
    FIELD_TYPE_DOUBLE_ARRAY: ClassVar[int]
    FIELD_TYPE_LONG_DOUBLE_ARRAY: ClassVar[int]
    FIELD_TYPE_CHAR_ARRAY: ClassVar[int]
    FIELD_TYPE_WCHAR_ARRAY: ClassVar[int]
    FIELD_TYPE_BOOLEAN_ARRAY: ClassVar[int]
    FIELD_TYPE_BYTE_ARRAY: ClassVar[int]
    FIELD_TYPE_STRING_ARRAY: ClassVar[int]
    FIELD_TYPE_WSTRING_ARRAY: ClassVar[int]
    FIELD_TYPE_FIXED_STRING_ARRAY: ClassVar[int]
    FIELD_TYPE_FIXED_WSTRING_ARRAY: ClassVar[int]
    FIELD_TYPE_BOUNDED_STRING_ARRAY: ClassVar[int]
    FIELD_TYPE_BOUNDED_WSTRING_ARRAY: ClassVar[int]
    FIELD_TYPE_NESTED_TYPE_BOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_INT8_BOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_UINT8_BOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_INT16_BOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_UINT16_BOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_INT32_BOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_UINT32_BOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_INT64_BOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_UINT64_BOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_FLOAT_BOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_DOUBLE_BOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_LONG_DOUBLE_BOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_CHAR_BOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_WCHAR_BOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_BOOLEAN_BOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_BYTE_BOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_STRING_BOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_WSTRING_BOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_FIXED_STRING_BOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_FIXED_WSTRING_BOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_BOUNDED_STRING_BOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_BOUNDED_WSTRING_BOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_NESTED_TYPE_UNBOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_INT8_UNBOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_UINT8_UNBOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_INT16_UNBOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_UINT16_UNBOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_INT32_UNBOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_UINT32_UNBOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_INT64_UNBOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_UINT64_UNBOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_FLOAT_UNBOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_DOUBLE_UNBOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_LONG_DOUBLE_UNBOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_CHAR_UNBOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_WCHAR_UNBOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_BOOLEAN_UNBOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_BYTE_UNBOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_STRING_UNBOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_WSTRING_UNBOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_FIXED_STRING_UNBOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_FIXED_WSTRING_UNBOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_BOUNDED_STRING_UNBOUNDED_SEQUENCE: ClassVar[int]
    FIELD_TYPE_BOUNDED_WSTRING_UNBOUNDED_SEQUENCE: ClassVar[int]
    type_id: int
    capacity: int
    string_capacity: int
    nested_type_name: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            type_id: int = ...,
            capacity: int = ...,
            string_capacity: int = ...,
            nested_type_name: str = ...,
        ) -> None: ...


class Field(Message, type_name="type_description_interfaces/msg/Field"):
    """type_description_interfaces/msg/Field: Represents a single field in a type."""

    __slots__ = (
        "name",
        "type",
        "default_value",
    )
    name: str
    type: FieldType
    default_value: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            name: str = ...,
            type: FieldType = ...,
            default_value: str = ...,
        ) -> None: ...


class IndividualTypeDescription(
    Message, type_name="type_description_interfaces/msg/IndividualTypeDescription"
):
    """type_description_interfaces/msg/IndividualTypeDescription: Represents a single type, without the types it references, if any."""

    __slots__ = (
        "type_name",
        "fields",
    )
    type_name: str
    fields: list[Field]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            type_name: str = ...,
            fields: Sequence[Field] = ...,
        ) -> None: ...


class KeyValue(Message, type_name="type_description_interfaces/msg/KeyValue"):
    """type_description_interfaces/msg/KeyValue: Represents an arbitrary key-value pair for application-specific information."""

    __slots__ = (
        "key",
        "value",
    )
    key: str
    value: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            key: str = ...,
            value: str = ...,
        ) -> None: ...


class TypeDescription(Message, type_name="type_description_interfaces/msg/TypeDescription"):
    """type_description_interfaces/msg/TypeDescription: Represents a complete type description, including the type itself as well as the types it references."""

    __slots__ = (
        "type_description",
        "referenced_type_descriptions",
    )
    type_description: IndividualTypeDescription
    referenced_type_descriptions: list[IndividualTypeDescription]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            type_description: IndividualTypeDescription = ...,
            referenced_type_descriptions: Sequence[IndividualTypeDescription] = ...,
        ) -> None: ...


class TypeSource(Message, type_name="type_description_interfaces/msg/TypeSource"):
    """type_description_interfaces/msg/TypeSource: Represents the original source of a ROS 2 interface definition."""

    __slots__ = (
        "type_name",
        "encoding",
        "raw_file_contents",
    )
    type_name: str
    encoding: str
    raw_file_contents: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            type_name: str = ...,
            encoding: str = ...,
            raw_file_contents: str = ...,
        ) -> None: ...


class GetTypeDescription_Request(
    Message, type_name="type_description_interfaces/srv/GetTypeDescription_Request"
):
    """type_description_interfaces/srv/GetTypeDescription_Request: ROS interface type name, in PACKAGE/NAMESPACE/TYPENAME format."""

    __slots__ = (
        "type_name",
        "type_hash",
        "include_type_sources",
    )
    type_name: str
    type_hash: str
    include_type_sources: bool

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            type_name: str = ...,
            type_hash: str = ...,
            include_type_sources: bool = ...,
        ) -> None: ...


class GetTypeDescription_Response(
    Message, type_name="type_description_interfaces/srv/GetTypeDescription_Response"
):
    """type_description_interfaces/srv/GetTypeDescription_Response: True if the type description information is available and populated in the response."""

    __slots__ = (
        "successful",
        "failure_reason",
        "type_description",
        "type_sources",
        "extra_information",
    )
    successful: bool
    failure_reason: str
    type_description: TypeDescription
    type_sources: list[TypeSource]
    extra_information: list[KeyValue]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            successful: bool = ...,
            failure_reason: str = ...,
            type_description: TypeDescription = ...,
            type_sources: Sequence[TypeSource] = ...,
            extra_information: Sequence[KeyValue] = ...,
        ) -> None: ...


class GetTypeDescription(Service, type_name="type_description_interfaces/srv/GetTypeDescription"):
    """type_description_interfaces/srv/GetTypeDescription: call with a GetTypeDescription.Request, answered with a GetTypeDescription.Response."""

    Request = GetTypeDescription_Request
    Response = GetTypeDescription_Response


__all__ = [
    "Field",
    "FieldType",
    "GetTypeDescription",
    "GetTypeDescription_Request",
    "GetTypeDescription_Response",
    "IndividualTypeDescription",
    "KeyValue",
    "TypeDescription",
    "TypeSource",
]
