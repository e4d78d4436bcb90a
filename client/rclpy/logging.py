"""``rclpy.logging``: loggers by name with rcutils' severities, ROS 2's console lines, and the
node's logger (which also publishes on /rosout) with rclpy's ``once``/``skip_first``/``throttle``."""

from __future__ import annotations

import sys
import time
import warnings
from enum import IntEnum
from typing import Any

from node_runtime.bus.node import NodeLogger
from rclpy._console import console_line, effective_level, own_level, set_level


class LoggingSeverity(IntEnum):
    UNSET = 0
    DEBUG = 10
    INFO = 20
    WARN = 30
    ERROR = 40
    FATAL = 50


class _Filters:
    """rclpy's per-call-site options: ``once``, ``skip_first``, ``throttle_duration_sec``."""

    def __init__(self) -> None:
        self._seen: dict[tuple[str, int, int], float] = {}

    def allow(
        self, *, once: bool = False, skip_first: bool = False, throttle_duration_sec: float = 0.0
    ) -> bool:
        if not (once or skip_first or throttle_duration_sec):
            return True
        frame = sys._getframe(3)  # the caller of info()/warn()/...
        # rclpy's call site: a file's line and the instruction in it (two calls on one line are two)
        site = (frame.f_code.co_filename, frame.f_lineno, frame.f_lasti)
        now = time.monotonic()
        last = self._seen.get(site)
        self._seen[site] = now if last is None or not once else last
        if last is None:
            return not skip_first
        if once:
            return False
        if throttle_duration_sec and now - last < throttle_duration_sec:
            self._seen[site] = last
            return False
        return True


def _warn_deprecated() -> None:
    """rclpy's warn(): it still logs, and warns (as Python shows a DeprecationWarning, at the
    student's line) that warning() is its name now."""
    warnings.warn(
        "Deprecated in favor of :py:classmethod:RcutilsLogger.warning:.", DeprecationWarning, stacklevel=3
    )


class RcutilsLogger:
    def __init__(self, name: str = "") -> None:
        self.name = name
        self._filters = _Filters()

    def _log(self, level: int, msg: Any, options: dict[str, Any]) -> bool:
        """Whether it logged (rclpy's result): False when the level or a filter held it back."""
        if level >= effective_level(self.name) and self._filters.allow(**options):
            console_line(level, self.name, str(msg))
            return True
        return False

    def debug(self, msg: Any, **options: Any) -> bool:
        return self._log(10, msg, options)

    def info(self, msg: Any, **options: Any) -> bool:
        return self._log(20, msg, options)

    def warning(self, msg: Any, **options: Any) -> bool:
        return self._log(30, msg, options)

    def warn(self, msg: Any, **options: Any) -> bool:
        _warn_deprecated()
        return self._log(30, msg, options)

    def error(self, msg: Any, **options: Any) -> bool:
        return self._log(40, msg, options)

    def fatal(self, msg: Any, **options: Any) -> bool:
        return self._log(50, msg, options)

    def get_child(self, name: str) -> RcutilsLogger:
        return RcutilsLogger(f"{self.name}.{name}" if self.name else name)

    def set_level(self, level: int) -> bool:
        set_level(self.name, int(level))
        return True

    def get_effective_level(self) -> LoggingSeverity:
        return LoggingSeverity(effective_level(self.name))

    def is_enabled_for(self, severity: int) -> bool:
        return int(severity) >= effective_level(self.name)


class NodeRcutilsLogger(NodeLogger):
    """``node.get_logger()``: named by the node, echoed on /rosout."""

    def __init__(self, node: Any) -> None:
        super().__init__(node)  # named as rcl names a node's logger: ``ns.name``
        self._filters = _Filters()

    def _emit(self, level: str, severity: int, msg: Any, options: dict[str, Any]) -> bool:
        if severity >= effective_level(self.name) and self._filters.allow(**options):
            self._log(level, msg)
            return True
        return False

    def debug(self, msg: Any, **options: Any) -> bool:  # type: ignore[override]
        return self._emit("debug", 10, msg, options)

    def info(self, msg: Any, **options: Any) -> bool:  # type: ignore[override]
        return self._emit("info", 20, msg, options)

    def warning(self, msg: Any, **options: Any) -> bool:  # type: ignore[override]
        return self._emit("warn", 30, msg, options)

    def warn(self, msg: Any, **options: Any) -> bool:  # type: ignore[override]
        _warn_deprecated()
        return self._emit("warn", 30, msg, options)

    def error(self, msg: Any, **options: Any) -> bool:  # type: ignore[override]
        return self._emit("error", 40, msg, options)

    def fatal(self, msg: Any, **options: Any) -> bool:  # type: ignore[override]
        return self._emit("fatal", 50, msg, options)

    def set_level(self, level: int) -> bool:
        set_level(self.name, int(level))
        return True

    def get_effective_level(self) -> LoggingSeverity:
        return LoggingSeverity(effective_level(self.name))

    def is_enabled_for(self, severity: int) -> bool:
        return int(severity) >= effective_level(self.name)

    def get_child(self, name: str) -> RcutilsLogger:
        return RcutilsLogger(f"{self.name}.{name}")


def get_logger(name: str) -> RcutilsLogger:
    return RcutilsLogger(name)


def set_logger_level(name: str, level: int, detailed_error: bool = False) -> None:
    """ValueError for a level that is not a severity (rclpy's)."""
    set_level(name, int(LoggingSeverity(level)))


def get_logger_level(name: str) -> LoggingSeverity:
    """The level set for logger ``name`` itself (UNSET when none was)."""
    return LoggingSeverity(own_level(name))


def get_logging_severity_from_string(log_severity: str) -> LoggingSeverity:
    try:
        return LoggingSeverity[log_severity.strip().upper()]
    except KeyError:
        raise RuntimeError(f"invalid log severity {log_severity!r}") from None


def get_logger_effective_level(name: str) -> LoggingSeverity:
    return LoggingSeverity(effective_level(name))


__all__ = [
    "LoggingSeverity",
    "RcutilsLogger",
    "get_logger",
    "get_logger_effective_level",
    "get_logger_level",
    "get_logging_severity_from_string",
    "set_logger_level",
]
