"""turtlesim's path image: the lines turtles' pens drew, and the color a turtle's sensor reads.

Pixels are (column, row), rows counted down from the top, as in turtlesim's window. Where no pen
drew, the image is turtlesim's cleared one (transparent white), which reads as white.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

STEP_PX = 0.5  # spacing of the pen's stamps along a line


class Rgb(NamedTuple):
    r: int
    g: int
    b: int


CLEARED = Rgb(255, 255, 255)


class Canvas:
    def __init__(self, width_px: int, height_px: int) -> None:
        self.pixels: npt.NDArray[np.uint8] = np.empty((height_px, width_px, 3), dtype=np.uint8)
        self.clear()

    def clear(self) -> None:
        self.pixels[:] = CLEARED

    def color_at(self, pixel: tuple[float, float]) -> Rgb:
        """The color at the pixel nearest ``pixel``; white outside the image."""
        column, row = (math.floor(v + 0.5) for v in pixel)
        height, width = self.pixels.shape[:2]
        if not (0 <= column < width and 0 <= row < height):
            return CLEARED
        r, g, b = (int(v) for v in self.pixels[row, column])
        return Rgb(r, g, b)

    def draw_line(
        self, start: tuple[float, float], end: tuple[float, float], color: Rgb, width_px: int
    ) -> None:
        """A pen stroke ``width_px`` wide from ``start`` to ``end`` (square ends)."""
        length = math.dist(start, end)
        stamps = max(1, math.ceil(length / STEP_PX)) + 1
        height, width = self.pixels.shape[:2]
        half = width_px / 2.0
        for t in np.linspace(0.0, 1.0, stamps):
            x = start[0] + (end[0] - start[0]) * t
            y = start[1] + (end[1] - start[1]) * t
            left, right = max(0, math.floor(x - half + 0.5)), min(width, math.floor(x + half + 0.5))
            top, bottom = max(0, math.floor(y - half + 0.5)), min(height, math.floor(y + half + 0.5))
            if left < right and top < bottom:
                self.pixels[top:bottom, left:right] = color
