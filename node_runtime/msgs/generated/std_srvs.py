"""std_srvs: generated from ROS 2's definitions (the wheels node_runtime/msgs/ros_packages.txt pins) by `python -m node_runtime.msgs.generate`; do not edit."""

from __future__ import annotations

from typing import TYPE_CHECKING

from node_runtime.msgs._base import Message, Service


class Empty_Request(Message, type_name="std_srvs/srv/Empty_Request"):
    """std_srvs/srv/Empty_Request"""

    __slots__ = ()


class Empty_Response(Message, type_name="std_srvs/srv/Empty_Response"):
    """std_srvs/srv/Empty_Response"""

    __slots__ = ()


class SetBool_Request(Message, type_name="std_srvs/srv/SetBool_Request"):
    """std_srvs/srv/SetBool_Request"""

    __slots__ = ("data",)
    data: bool

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            data: bool = ...,
        ) -> None: ...


class SetBool_Response(Message, type_name="std_srvs/srv/SetBool_Response"):
    """std_srvs/srv/SetBool_Response"""

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


class Trigger_Request(Message, type_name="std_srvs/srv/Trigger_Request"):
    """std_srvs/srv/Trigger_Request"""

    __slots__ = ()


class Trigger_Response(Message, type_name="std_srvs/srv/Trigger_Response"):
    """std_srvs/srv/Trigger_Response"""

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


class Empty(Service, type_name="std_srvs/srv/Empty"):
    """std_srvs/srv/Empty: call with a Empty.Request, answered with a Empty.Response."""

    Request = Empty_Request
    Response = Empty_Response


class SetBool(Service, type_name="std_srvs/srv/SetBool"):
    """std_srvs/srv/SetBool: call with a SetBool.Request, answered with a SetBool.Response."""

    Request = SetBool_Request
    Response = SetBool_Response


class Trigger(Service, type_name="std_srvs/srv/Trigger"):
    """std_srvs/srv/Trigger: call with a Trigger.Request, answered with a Trigger.Response."""

    Request = Trigger_Request
    Response = Trigger_Response


__all__ = [
    "Empty",
    "Empty_Request",
    "Empty_Response",
    "SetBool",
    "SetBool_Request",
    "SetBool_Response",
    "Trigger",
    "Trigger_Request",
    "Trigger_Response",
]
