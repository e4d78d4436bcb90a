"""example_interfaces: generated from server/msgs/interfaces/example_interfaces by `python -m server.msgs.generate`; do not edit."""

from __future__ import annotations

from typing import TYPE_CHECKING

from .._base import Message, Service


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


class AddTwoInts(Service, type_name="example_interfaces/srv/AddTwoInts"):
    """example_interfaces/srv/AddTwoInts: call with a AddTwoInts.Request, answered with a AddTwoInts.Response."""

    Request = AddTwoInts_Request
    Response = AddTwoInts_Response


__all__ = [
    "AddTwoInts",
    "AddTwoInts_Request",
    "AddTwoInts_Response",
]
