"""``rclpy.logging.get_logger(name)``: ROS 2's console lines, for code outside a node."""

from __future__ import annotations

from typing import Any

from ._console import console_line, set_threshold

LoggingSeverity = {"DEBUG": 10, "INFO": 20, "WARN": 30, "ERROR": 40, "FATAL": 50}


class RcutilsLogger:
    def __init__(self, name: str) -> None:
        self.name = name

    def debug(self, msg: Any) -> None:
        console_line(10, self.name, str(msg))

    def info(self, msg: Any) -> None:
        console_line(20, self.name, str(msg))

    def warning(self, msg: Any) -> None:
        console_line(30, self.name, str(msg))

    warn = warning

    def error(self, msg: Any) -> None:
        console_line(40, self.name, str(msg))

    def fatal(self, msg: Any) -> None:
        console_line(50, self.name, str(msg))

    def set_level(self, level: int) -> None:
        set_threshold(int(level))


def get_logger(name: str) -> RcutilsLogger:
    return RcutilsLogger(name)
