"""A bounded record of what happened, for a check's evidence: the newest entries, oldest dropped."""

from __future__ import annotations

from collections import deque
from typing import Any

from server.world.checkpoints.events import Source


class Timeline:
    def __init__(self, maxlen: int) -> None:
        self._entries: deque[dict[str, Any]] = deque(maxlen=maxlen)

    def add(self, t_s: float, what: str, value: Any, source: Source | None = None) -> None:
        entry: dict[str, Any] = {"t_s": round(t_s, 3), "what": what, "value": value}
        if source is not None:
            entry["by"] = source.node
            entry["process"] = source.process
            entry["student"] = source.student
        self._entries.append(entry)

    def clear(self) -> None:
        self._entries.clear()

    def since(self, t_s: float) -> list[dict[str, Any]]:
        return [e for e in self._entries if e["t_s"] >= round(t_s, 3)]

    def entries(self) -> list[dict[str, Any]]:
        return list(self._entries)


class Track:
    """The drone's positions, at most one every ``every_s``, the newest ``maxlen``."""

    def __init__(self, maxlen: int = 900, every_s: float = 0.2) -> None:
        self._points: deque[list[float]] = deque(maxlen=maxlen)
        self.every_s = every_s
        self._last_s = -1e18

    def add(self, t_s: float, xyz: tuple[float, float, float]) -> None:
        if t_s - self._last_s >= self.every_s:
            self._last_s = t_s
            self._points.append([round(t_s, 3), *(round(v, 3) for v in xyz)])

    def clear(self) -> None:
        self._points.clear()
        self._last_s = -1e18

    def since(self, t_s: float) -> list[list[float]]:
        return [p for p in self._points if p[0] >= t_s]
