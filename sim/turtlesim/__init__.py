"""turtlesim's turtles without a window: kinematics, pens, the canvas their color sensors read."""

from sim.turtlesim.canvas import Canvas, Rgb
from sim.turtlesim.turtle import (
    COMMAND_TIMEOUT_S,
    SIZE_M,
    UPDATE_PERIOD_S,
    Pen,
    Reading,
    Rotation,
    Teleport,
    Turtle,
    normalize_angle,
)
from sim.turtlesim.world import CENTER_M, TurtleWorld

__all__ = [
    "CENTER_M",
    "COMMAND_TIMEOUT_S",
    "SIZE_M",
    "UPDATE_PERIOD_S",
    "Canvas",
    "Pen",
    "Reading",
    "Rgb",
    "Rotation",
    "Teleport",
    "Turtle",
    "TurtleWorld",
    "normalize_angle",
]
