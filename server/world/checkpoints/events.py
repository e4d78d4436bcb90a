"""What the checks see: the lab's events as small typed values, each stamped with the bus's clock.

The watcher (watcher.py) turns messages on the bus, launches and graph changes into these; a check
only ever reads them, so it can be fed by hand in a test with a manual clock.
"""

from __future__ import annotations

from dataclasses import dataclass

LAB = "the lab"  # the process of a message sent by a node inside the app


@dataclass(frozen=True)
class Source:
    """Who published a message: its node, its process and whether that is the student's own code
    (a process started from a file of the student's workspace, or one the lab did not start)."""

    node: str  # fully qualified; "" when not known
    process: str = LAB  # "process 1234", "zenoh:ab12cd34", or LAB
    student: bool = False


UNKNOWN = Source("")


@dataclass(frozen=True)
class KeyDown:
    """A key pressed, as the keyboard node published it on /keydown (an SDL key code)."""

    t_s: float
    code: int
    source: Source


@dataclass(frozen=True)
class Abort:
    """A message on /abort_takeoff."""

    t_s: float
    value: bool
    source: Source


@dataclass(frozen=True)
class CmdVel:
    """The rocket's velocity command on /cmd_vel, m/s (positive: lift-off)."""

    t_s: float
    value_mps: float


@dataclass(frozen=True)
class Countdown:
    """A count on /countdown, s before lift-off, and who counts (two rockets may count at once)."""

    t_s: float
    value: int
    source: Source = UNKNOWN


@dataclass(frozen=True)
class Setpoint:
    """A position setpoint on /uav/input/position, m in the world frame."""

    t_s: float
    xyz: tuple[float, float, float]
    source: Source


@dataclass(frozen=True)
class Gps:
    """The drone's position on /uav/sensors/gps, m in the world frame."""

    t_s: float
    xyz: tuple[float, float, float]


@dataclass(frozen=True)
class LaunchedNode:
    pkg: str
    exec: str
    name: str | None
    student: bool  # the student's own file (it runs as a process)


@dataclass(frozen=True)
class Launch:
    """A launch file started (at the lab's start or through the API)."""

    t_s: float
    file: str  # its path in the workspace, or "<file> of the package <pkg>" (watcher.launch_label)
    text: str  # the file's text, at most MAX_LAUNCH_TEXT characters
    in_workspace: bool  # the file is in the student's workspace
    nodes: tuple[LaunchedNode, ...]


MAX_LAUNCH_TEXT = 16 * 1024

Event = KeyDown | Abort | CmdVel | Countdown | Setpoint | Gps | Launch
