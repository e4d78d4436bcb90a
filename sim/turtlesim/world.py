"""turtlesim's window without the window: its turtles by name, their canvas, spawn, kill, reset.

A turtle spawned without a name is ``turtleN`` with the next free N (counting from 1 again after
a reset); a name already taken spawns nothing. ``CENTER_M`` is where turtlesim puts its first.
"""

from __future__ import annotations

import numpy as np

from sim.turtlesim.canvas import Canvas
from sim.turtlesim.turtle import CANVAS_PX, SIZE_M, Reading, Turtle

CENTER_M = SIZE_M / 2.0


class TurtleWorld:
    def __init__(self) -> None:
        self.canvas = Canvas(CANVAS_PX, CANVAS_PX)
        self.turtles: dict[str, Turtle] = {}
        self._last_id = 0

    def spawn(self, name: str, x_m: float, y_m: float, theta_rad: float, now_s: float) -> str | None:
        """The new turtle's name, or None if ``name`` is taken."""
        if not name:
            while not name or name in self.turtles:
                self._last_id += 1
                name = f"turtle{self._last_id}"
        elif name in self.turtles:
            return None
        x_m, y_m, theta_rad = (float(np.float32(v)) for v in (x_m, y_m, theta_rad))  # turtlesim's floats
        self.turtles[name] = Turtle(x_m, y_m, theta_rad, last_command_s=now_s)
        return name

    def kill(self, name: str) -> bool:
        return self.turtles.pop(name, None) is not None

    def reset(self) -> None:
        """No turtle, a cleared canvas, and the next unnamed turtle ``turtle1`` again (turtlesim
        then spawns one at ``CENTER_M``)."""
        self.turtles.clear()
        self._last_id = 0
        self.canvas.clear()

    def step(self, now_s: float) -> dict[str, Reading]:
        """Every turtle one frame on, in the order of their names (as turtlesim's map holds them)."""
        return {name: self.turtles[name].step(now_s, self.canvas) for name in sorted(self.turtles)}
