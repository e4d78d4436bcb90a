"""The frames of the WebSockets the page opens: the key channel's (``/ws/keys``), the topic echo's
(``/ws/topics/{topic}``) and a run's output (``/ws/launches/{id}/output``).

The output's frames are built in server/services/launch/output.py, below the API, and declared
there; they are named here with the rest, for the page's types (api/typescript.py).
"""

from __future__ import annotations

from typing import Annotated, Any, Literal, NotRequired

from pydantic import Field
from typing_extensions import TypedDict

from server.services.launch.output import (
    DroppedFrame,
    EndFrame,
    ExitFrame,
    JoinedFrame,
    LineFrame,
    StartedFrame,
    WaitingFrame,
)

__all__ = [
    "ControlFrame",
    "DroppedFrame",
    "EchoFrame",
    "EndFrame",
    "ExitFrame",
    "JoinedFrame",
    "KeyChannelError",
    "KeyFrame",
    "LineFrame",
    "OutputFrame",
    "StartedFrame",
    "WaitingFrame",
]


class KeyFrame(TypedDict):
    """A key going down or up, as the page sends it; the flags are the modifiers held then
    (server/peripherals/devices/keymap.py's names: sided, or unsided when the side is unknown)."""

    type: Literal["keydown", "keyup"]
    key: str  # KeyboardEvent.key
    code: NotRequired[str]  # KeyboardEvent.code
    location: NotRequired[int]  # KeyboardEvent.location: 0 standard, 1 left, 2 right, 3 keypad
    repeat: NotRequired[bool]
    t: NotRequired[float]  # the page's performance.now() (ms), for its own timing
    lshift: NotRequired[bool]
    rshift: NotRequired[bool]
    lctrl: NotRequired[bool]
    rctrl: NotRequired[bool]
    lalt: NotRequired[bool]
    ralt: NotRequired[bool]
    lmeta: NotRequired[bool]
    rmeta: NotRequired[bool]
    num: NotRequired[bool]
    caps: NotRequired[bool]
    mode: NotRequired[bool]
    shift: NotRequired[bool]
    ctrl: NotRequired[bool]
    alt: NotRequired[bool]
    meta: NotRequired[bool]


class ControlFrame(TypedDict):
    """``release_all``: release every key this channel holds; ``heartbeat``: the page is there."""

    type: Literal["release_all", "heartbeat"]


class KeyChannelError(TypedDict):
    """The server's only frame on this channel: why a frame did nothing."""

    type: Literal["error"]
    error: str


class EchoFrame(TypedDict):
    """One message on ``/ws/topics/{topic}``, as the page reads it."""

    topic: str
    type: str  # the message type, e.g. geometry_msgs/msg/PoseStamped
    msg: dict[str, Any]  # the message's JSON form
    received: float  # when the bus delivered it here (s, Unix epoch)
    dropped: NotRequired[int]  # messages this channel dropped so far (a slow client), when any


OutputFrame = Annotated[
    LineFrame | DroppedFrame | WaitingFrame | StartedFrame | JoinedFrame | ExitFrame | EndFrame,
    Field(
        discriminator="type",
        description="A frame of a run's output socket: its lines (the kept ones first), lines lost, "
        "a node waiting for its turn, each node process's start (its pid) and its node's arrival in the "
        "graph, each node's exit and, last, the group's end.",
    ),
]
