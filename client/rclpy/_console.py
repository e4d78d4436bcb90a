"""Log lines as ROS 2 prints them: ``[INFO] [1700000000.123456789] [node]: text``, on stderr."""

from __future__ import annotations

import sys
import time

SEVERITY = {10: "DEBUG", 20: "INFO", 30: "WARN", 40: "ERROR", 50: "FATAL"}
_threshold = 20


def set_threshold(level: int) -> None:
    global _threshold
    _threshold = level


def console_line(level: int, name: str, text: str) -> None:
    if level < _threshold:
        return
    stamp = time.time_ns()
    sys.stderr.write(
        f"[{SEVERITY.get(level, str(level))}] [{stamp // 10**9}.{stamp % 10**9:09d}] [{name}]: {text}\n"
    )
    sys.stderr.flush()
