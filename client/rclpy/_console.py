"""Log lines as ROS 2 prints them: ``[INFO] [1700000000.123456789] [node]: text``, on stderr."""

from __future__ import annotations

import sys
import time

SEVERITY = {10: "DEBUG", 20: "INFO", 30: "WARN", 40: "ERROR", 50: "FATAL"}
_threshold = 20
_levels: dict[str, int] = {}  # per logger name, as rcutils keeps them


def set_threshold(level: int) -> None:
    global _threshold
    _threshold = level


def set_level(name: str, level: int) -> None:
    """A logger's own level; 0 (UNSET) makes it follow the process's again."""
    if level:
        _levels[name] = level
    else:
        _levels.pop(name, None)


def own_level(name: str) -> int:
    """The level set for this logger itself; 0 (UNSET) when it follows the process's."""
    return _levels.get(name, 0)


def effective_level(name: str) -> int:
    return _levels.get(name, _threshold)


def console_line(level: int, name: str, text: str) -> None:
    if level < effective_level(name):
        return
    stamp = time.time_ns()
    sys.stderr.write(
        f"[{SEVERITY.get(level, str(level))}] [{stamp // 10**9}.{stamp % 10**9:09d}] [{name}]: {text}\n"
    )
    sys.stderr.flush()
