"""turtlesim: generated from server/msgs/interfaces/turtlesim by `python -m server.msgs.generate`; do not edit."""

from __future__ import annotations

from typing import TYPE_CHECKING

from .._base import Message, Service


class Color(Message, type_name="turtlesim/msg/Color"):
    """turtlesim/msg/Color: The color of the canvas under a turtle."""

    __slots__ = (
        "r",
        "g",
        "b",
    )
    r: int
    g: int
    b: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            r: int = ...,
            g: int = ...,
            b: int = ...,
        ) -> None: ...


class Pose(Message, type_name="turtlesim/msg/Pose"):
    """turtlesim/msg/Pose: A turtle's pose in turtlesim's window (meters, origin at the lower left) and its velocities."""

    __slots__ = (
        "x",
        "y",
        "theta",
        "linear_velocity",
        "angular_velocity",
    )
    x: float
    y: float
    theta: float
    linear_velocity: float
    angular_velocity: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            x: float = ...,
            y: float = ...,
            theta: float = ...,
            linear_velocity: float = ...,
            angular_velocity: float = ...,
        ) -> None: ...


class Kill_Request(Message, type_name="turtlesim/srv/Kill_Request"):
    """turtlesim/srv/Kill_Request: Remove the turtle of this name."""

    __slots__ = ("name",)
    name: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            name: str = ...,
        ) -> None: ...


class Kill_Response(Message, type_name="turtlesim/srv/Kill_Response"):
    """turtlesim/srv/Kill_Response"""

    __slots__ = ()


class SetPen_Request(Message, type_name="turtlesim/srv/SetPen_Request"):
    """turtlesim/srv/SetPen_Request: The turtle's pen: its color, its width in pixels (0 keeps 1), and off (non-zero lifts it)."""

    __slots__ = (
        "r",
        "g",
        "b",
        "width",
        "off",
    )
    r: int
    g: int
    b: int
    width: int
    off: int

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            r: int = ...,
            g: int = ...,
            b: int = ...,
            width: int = ...,
            off: int = ...,
        ) -> None: ...


class SetPen_Response(Message, type_name="turtlesim/srv/SetPen_Response"):
    """turtlesim/srv/SetPen_Response"""

    __slots__ = ()


class Spawn_Request(Message, type_name="turtlesim/srv/Spawn_Request"):
    """turtlesim/srv/Spawn_Request: A new turtle at (x, y) facing theta; with no name, turtlesim picks one and answers it."""

    __slots__ = (
        "x",
        "y",
        "theta",
        "name",
    )
    x: float
    y: float
    theta: float
    name: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            x: float = ...,
            y: float = ...,
            theta: float = ...,
            name: str = ...,
        ) -> None: ...


class Spawn_Response(Message, type_name="turtlesim/srv/Spawn_Response"):
    """turtlesim/srv/Spawn_Response"""

    __slots__ = ("name",)
    name: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            name: str = ...,
        ) -> None: ...


class TeleportAbsolute_Request(Message, type_name="turtlesim/srv/TeleportAbsolute_Request"):
    """turtlesim/srv/TeleportAbsolute_Request: Move the turtle to (x, y) facing theta."""

    __slots__ = (
        "x",
        "y",
        "theta",
    )
    x: float
    y: float
    theta: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            x: float = ...,
            y: float = ...,
            theta: float = ...,
        ) -> None: ...


class TeleportAbsolute_Response(Message, type_name="turtlesim/srv/TeleportAbsolute_Response"):
    """turtlesim/srv/TeleportAbsolute_Response"""

    __slots__ = ()


class TeleportRelative_Request(Message, type_name="turtlesim/srv/TeleportRelative_Request"):
    """turtlesim/srv/TeleportRelative_Request: Turn the turtle by angular, then move it linear meters ahead."""

    __slots__ = (
        "linear",
        "angular",
    )
    linear: float
    angular: float

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            linear: float = ...,
            angular: float = ...,
        ) -> None: ...


class TeleportRelative_Response(Message, type_name="turtlesim/srv/TeleportRelative_Response"):
    """turtlesim/srv/TeleportRelative_Response"""

    __slots__ = ()


class Kill(Service, type_name="turtlesim/srv/Kill"):
    """turtlesim/srv/Kill: call with a Kill.Request, answered with a Kill.Response."""

    Request = Kill_Request
    Response = Kill_Response


class SetPen(Service, type_name="turtlesim/srv/SetPen"):
    """turtlesim/srv/SetPen: call with a SetPen.Request, answered with a SetPen.Response."""

    Request = SetPen_Request
    Response = SetPen_Response


class Spawn(Service, type_name="turtlesim/srv/Spawn"):
    """turtlesim/srv/Spawn: call with a Spawn.Request, answered with a Spawn.Response."""

    Request = Spawn_Request
    Response = Spawn_Response


class TeleportAbsolute(Service, type_name="turtlesim/srv/TeleportAbsolute"):
    """turtlesim/srv/TeleportAbsolute: call with a TeleportAbsolute.Request, answered with a TeleportAbsolute.Response."""

    Request = TeleportAbsolute_Request
    Response = TeleportAbsolute_Response


class TeleportRelative(Service, type_name="turtlesim/srv/TeleportRelative"):
    """turtlesim/srv/TeleportRelative: call with a TeleportRelative.Request, answered with a TeleportRelative.Response."""

    Request = TeleportRelative_Request
    Response = TeleportRelative_Response


__all__ = [
    "Color",
    "Kill",
    "Kill_Request",
    "Kill_Response",
    "Pose",
    "SetPen",
    "SetPen_Request",
    "SetPen_Response",
    "Spawn",
    "Spawn_Request",
    "Spawn_Response",
    "TeleportAbsolute",
    "TeleportAbsolute_Request",
    "TeleportAbsolute_Response",
    "TeleportRelative",
    "TeleportRelative_Request",
    "TeleportRelative_Response",
]
