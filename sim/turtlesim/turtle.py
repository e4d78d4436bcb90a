"""One turtle of turtlesim: its pose, the velocity it was last commanded, its pen and teleports.

Units as turtlesim's: meters in a square window of ``SIZE_M`` a side, the origin at its lower
left, ``theta`` in radians counter-clockwise from +x, kept in [-pi, pi). A turtle steps by a fixed
``UPDATE_PERIOD_S`` (turtlesim integrates its 16 ms frame period, whatever time really passed),
moves along its heading at ``linear.x`` (and sideways at ``linear.y`` when holonomic), turns at
``angular.z``, stops when no command came for ``COMMAND_TIMEOUT_S``, and is clamped to the
window (saying so). Teleports wait for the next step, as turtlesim's do, and run in order.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from sim.turtlesim.canvas import Canvas, Rgb

UPDATE_PERIOD_S = 0.016  # turtlesim's frame timer: 62.5 steps a second
COMMAND_TIMEOUT_S = 1.0  # a velocity older than this stops the turtle
METER_PX = 45  # pixels per meter: the height of turtlesim's turtle images
CANVAS_PX = 500  # the window's side in pixels
SIZE_M = (CANVAS_PX - 1) / METER_PX  # the window's side in meters (11.088...)
PEN = Rgb(0xB3, 0xB8, 0xFF)  # a new turtle's pen color
PEN_WIDTH_PX = 3
GOAL_TOLERANCE_RAD = 0.02  # a rotate_absolute goal is reached this close


def _float32(value: float) -> float:
    return float(np.float32(value))


def normalize_angle(angle_rad: float) -> float:
    """The same angle in [-pi, pi)."""
    return angle_rad - 2.0 * math.pi * math.floor((angle_rad + math.pi) / (2.0 * math.pi))


@dataclass(frozen=True)
class Pen:
    color: Rgb = PEN
    width_px: int = PEN_WIDTH_PX
    on: bool = True


@dataclass(frozen=True)
class Teleport:
    """To (x_m, y_m) facing theta_rad; relative: turn by theta_rad, then move linear_m ahead."""

    x_m: float = 0.0
    y_m: float = 0.0
    theta_rad: float = 0.0
    linear_m: float = 0.0
    relative: bool = False


@dataclass(frozen=True)
class Rotation:
    """A rotate_absolute goal's frame: how far is left to turn, how far it turned, whether it is there."""

    remaining_rad: float
    delta_rad: float
    done: bool


@dataclass(frozen=True)
class Reading:
    """What a step leaves: the pose message's values, the color under the turtle, and where it
    was when it had to be clamped to the window (meters, y counted down from the top edge, as
    turtlesim reports it)."""

    x_m: float
    y_m: float
    theta_rad: float
    linear_velocity_mps: float
    angular_velocity_radps: float
    color: Rgb
    clamped_from: tuple[float, float] | None = None
    rotation: Rotation | None = None  # with a rotate_absolute goal under way


@dataclass
class Turtle:
    x_m: float
    y_m: float
    theta_rad: float
    last_command_s: float
    linear_x_mps: float = 0.0
    linear_y_mps: float = 0.0
    angular_radps: float = 0.0
    pen: Pen = field(default_factory=Pen)
    teleports: list[Teleport] = field(default_factory=list)
    heading_goal_rad: float | None = None  # a rotate_absolute goal: turn at 1 rad/s until facing it
    goal_start_rad: float = 0.0  # the heading when the goal came

    def command(self, linear_x_mps: float, linear_y_mps: float, angular_radps: float, now_s: float) -> None:
        """A velocity command (``linear_y_mps`` is 0 unless the turtle is holonomic)."""
        self.last_command_s = now_s
        self.linear_x_mps, self.linear_y_mps, self.angular_radps = linear_x_mps, linear_y_mps, angular_radps

    def rotate_to(self, theta_rad: float) -> None:
        """Turn to face ``theta_rad`` (in place of any goal before it)."""
        self.heading_goal_rad, self.goal_start_rad = theta_rad, self.theta_rad

    def stop(self) -> None:
        """No goal and no velocity (a goal that ended or was canceled)."""
        self.heading_goal_rad = None
        self.linear_x_mps = self.linear_y_mps = self.angular_radps = 0.0

    def set_pen(self, r: int, g: int, b: int, width_px: int, off: bool) -> None:
        """turtlesim's SetPen: off lifts the pen and keeps its color; width 0 is a 1 px pen."""
        if off:
            self.pen = Pen(self.pen.color, self.pen.width_px, on=False)
        else:
            self.pen = Pen(Rgb(r, g, b), width_px or 1, on=True)

    def step(self, now_s: float, canvas: Canvas) -> Reading:
        for teleport in self.teleports:
            before = self._pixel()
            if teleport.relative:
                self.theta_rad += teleport.theta_rad
                self.x_m += math.cos(self.theta_rad) * teleport.linear_m
                self.y_m += math.sin(self.theta_rad) * teleport.linear_m
            else:
                self.x_m, self.y_m = teleport.x_m, min(SIZE_M, teleport.y_m)
                self.theta_rad = teleport.theta_rad
            self._draw(canvas, before)
        self.teleports.clear()
        rotation = self._rotate(now_s)
        if now_s - self.last_command_s > COMMAND_TIMEOUT_S:
            self.linear_x_mps = self.linear_y_mps = self.angular_radps = 0.0
        before = self._pixel()
        dt = UPDATE_PERIOD_S
        self.theta_rad = normalize_angle(self.theta_rad + self.angular_radps * dt)
        cos, sin = math.cos(self.theta_rad), math.sin(self.theta_rad)
        self.x_m += (cos * self.linear_x_mps - sin * self.linear_y_mps) * dt
        self.y_m += (sin * self.linear_x_mps + cos * self.linear_y_mps) * dt
        clamped_from = None
        if not (0.0 <= self.x_m <= SIZE_M and 0.0 <= self.y_m <= SIZE_M):
            clamped_from = (self.x_m, SIZE_M - self.y_m)
            self.x_m, self.y_m = min(max(self.x_m, 0.0), SIZE_M), min(max(self.y_m, 0.0), SIZE_M)
        reading = Reading(
            self.x_m,
            self.y_m,
            self.theta_rad,
            math.hypot(self.linear_x_mps, self.linear_y_mps),
            self.angular_radps,
            canvas.color_at(self._pixel()),
            clamped_from,
            rotation,
        )
        self._draw(canvas, before)
        return reading

    def _rotate(self, now_s: float) -> Rotation | None:
        """A goal's frame, as turtlesim computes it (the heading as a float32): within 0.02 rad it
        is reached and the turtle stops, else it turns toward it at 1 rad/s as if just told to."""
        if self.heading_goal_rad is None:
            return None
        heading = _float32(self.theta_rad)
        goal = normalize_angle(self.heading_goal_rad)
        remaining = normalize_angle(goal - heading)
        delta = normalize_angle(_float32(self.goal_start_rad - self.theta_rad))
        if abs(normalize_angle(heading - goal)) < GOAL_TOLERANCE_RAD:
            self.stop()
            return Rotation(remaining, delta, done=True)
        self.linear_x_mps = self.linear_y_mps = 0.0
        self.angular_radps = -1.0 if remaining < 0.0 else 1.0
        self.last_command_s = now_s
        return Rotation(remaining, delta, done=False)

    def _pixel(self) -> tuple[float, float]:
        """Where the turtle is on the canvas: (column, row) in pixels, rows counted down."""
        return self.x_m * METER_PX, (SIZE_M - self.y_m) * METER_PX

    def _draw(self, canvas: Canvas, start: tuple[float, float]) -> None:
        end = self._pixel()
        if self.pen.on and end != start:
            canvas.draw_line(start, end, self.pen.color, self.pen.width_px)
