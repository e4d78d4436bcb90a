"""Live plots in the page, like rqt_plot: a few series against time, a bounded history."""

from __future__ import annotations

from collections import deque
from typing import Any

import numpy as np
from viser import uplot


class TimePlot:
    """One uPlot chart; ``append`` is cheap, ``flush`` sends the data (call it a few times a second)."""

    def __init__(
        self,
        gui: Any,
        title: str,
        labels: tuple[str, ...],
        colors: tuple[str, ...],
        window_s: float | None = None,
        max_points: int = 2000,
    ) -> None:
        self.window_s = window_s
        self._rows: deque[tuple[float, ...]] = deque(maxlen=max_points)
        self._dirty = False
        series = (
            uplot.Series(label="t (s)"),
            *(
                uplot.Series(label=label, stroke=color, width=2)
                for label, color in zip(labels, colors, strict=True)
            ),
        )
        empty = tuple(np.zeros(1) for _ in range(len(labels) + 1))
        self.handle = gui.add_uplot(
            empty, series, title=title, aspect=2.0, scales={"x": uplot.Scale(time=False)}
        )

    def append(self, t_s: float, *values: float) -> None:
        rows = self._rows
        rows.append((t_s, *values))
        if self.window_s is not None:  # what flush would leave out anyway: no need to keep it
            while rows[0][0] < t_s - self.window_s:
                rows.popleft()
        self._dirty = True

    def clear(self) -> None:
        self._rows.clear()
        self._dirty = True

    def flush(self) -> None:
        if not self._dirty or not self._rows:
            return
        self._dirty = False
        rows = np.asarray(self._rows, dtype=np.float64)
        if self.window_s is not None:
            rows = rows[rows[:, 0] >= rows[-1, 0] - self.window_s]
        self.handle.data = tuple(rows[:, i].copy() for i in range(rows.shape[1]))
