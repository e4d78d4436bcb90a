"""diagnostic_msgs: generated from ROS 2's definitions (the wheels node_runtime/msgs/ros_packages.txt pins) by `python -m node_runtime.msgs.generate`; do not edit."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, ClassVar

from node_runtime.msgs._base import Message, Service
from node_runtime.msgs.generated.std_msgs import Header


class KeyValue(Message, type_name="diagnostic_msgs/msg/KeyValue"):
    """diagnostic_msgs/msg/KeyValue: What to label this value when viewing."""

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


class DiagnosticStatus(Message, type_name="diagnostic_msgs/msg/DiagnosticStatus"):
    """diagnostic_msgs/msg/DiagnosticStatus: This message holds the status of an individual component of the robot."""

    __slots__ = (
        "level",
        "name",
        "message",
        "hardware_id",
        "values",
    )
    OK: ClassVar[int]
    WARN: ClassVar[int]
    ERROR: ClassVar[int]
    STALE: ClassVar[int]
    level: int
    name: str
    message: str
    hardware_id: str
    values: list[KeyValue]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            level: int = ...,
            name: str = ...,
            message: str = ...,
            hardware_id: str = ...,
            values: Sequence[KeyValue] = ...,
        ) -> None: ...


class DiagnosticArray(Message, type_name="diagnostic_msgs/msg/DiagnosticArray"):
    """diagnostic_msgs/msg/DiagnosticArray: This message is used to send diagnostic information about the state of the robot."""

    __slots__ = (
        "header",
        "status",
    )
    header: Header
    status: list[DiagnosticStatus]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            header: Header = ...,
            status: Sequence[DiagnosticStatus] = ...,
        ) -> None: ...


class AddDiagnostics_Request(Message, type_name="diagnostic_msgs/srv/AddDiagnostics_Request"):
    """diagnostic_msgs/srv/AddDiagnostics_Request: This service is used as part of the process for loading analyzers at runtime,"""

    __slots__ = ("load_namespace",)
    load_namespace: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            load_namespace: str = ...,
        ) -> None: ...


class AddDiagnostics_Response(Message, type_name="diagnostic_msgs/srv/AddDiagnostics_Response"):
    """diagnostic_msgs/srv/AddDiagnostics_Response: True if diagnostic aggregator was updated with new diagnostics, False"""

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


class SelfTest_Request(Message, type_name="diagnostic_msgs/srv/SelfTest_Request"):
    """diagnostic_msgs/srv/SelfTest_Request"""

    __slots__ = ()


class SelfTest_Response(Message, type_name="diagnostic_msgs/srv/SelfTest_Response"):
    """diagnostic_msgs/srv/SelfTest_Response"""

    __slots__ = (
        "id",
        "passed",
        "status",
    )
    id: str
    passed: int
    status: list[DiagnosticStatus]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            id: str = ...,
            passed: int = ...,
            status: Sequence[DiagnosticStatus] = ...,
        ) -> None: ...


class AddDiagnostics(Service, type_name="diagnostic_msgs/srv/AddDiagnostics"):
    """diagnostic_msgs/srv/AddDiagnostics: call with a AddDiagnostics.Request, answered with a AddDiagnostics.Response."""

    Request = AddDiagnostics_Request
    Response = AddDiagnostics_Response


class SelfTest(Service, type_name="diagnostic_msgs/srv/SelfTest"):
    """diagnostic_msgs/srv/SelfTest: call with a SelfTest.Request, answered with a SelfTest.Response."""

    Request = SelfTest_Request
    Response = SelfTest_Response


__all__ = [
    "AddDiagnostics",
    "AddDiagnostics_Request",
    "AddDiagnostics_Response",
    "DiagnosticArray",
    "DiagnosticStatus",
    "KeyValue",
    "SelfTest",
    "SelfTest_Request",
    "SelfTest_Response",
]
