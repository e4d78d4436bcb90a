"""rclpy's logger services, with ``Node(..., enable_logger_service=True)``: ``<node>/get_logger_levels``
and ``<node>/set_logger_levels`` (rcl_interfaces) read and set the process's loggers' levels, so
``ros2 service call`` changes what a running node logs."""

from __future__ import annotations

from typing import Any

from rclpy.logging import LoggingSeverity, get_logger_level, set_logger_level
from rclpy.qos import qos_profile_services_default


class LoggingService:
    def __init__(self, node: Any) -> None:
        try:
            from rcl_interfaces.msg import LoggerLevel, SetLoggerLevelsResult
            from rcl_interfaces.srv import GetLoggerLevels, SetLoggerLevels
        except ImportError as exc:
            raise RuntimeError(
                f"enable_logger_service: this lab's rcl_interfaces lack {exc.name or exc}"
            ) from None
        self._level_type, self._result_type = LoggerLevel, SetLoggerLevelsResult
        name = node.get_name()
        node.create_service(
            GetLoggerLevels,
            f"{name}/get_logger_levels",
            self._get_logger_levels,
            qos_profile=qos_profile_services_default,
        )
        node.create_service(
            SetLoggerLevels,
            f"{name}/set_logger_levels",
            self._set_logger_levels,
            qos_profile=qos_profile_services_default,
        )

    def _get_logger_levels(self, request: Any, response: Any) -> Any:
        response.levels = [
            self._level_type(name=name, level=int(get_logger_level(name))) for name in request.names
        ]
        return response

    def _set_logger_levels(self, request: Any, response: Any) -> Any:
        results = []
        for level in request.levels:
            result = self._result_type(successful=False)
            try:
                set_logger_level(level.name, LoggingSeverity(level.level))
                result.successful = True
            except ValueError:
                result.reason = "Failed reason: Invalid logger level."
            results.append(result)
        response.results = results
        return response


__all__ = ["LoggingService"]
