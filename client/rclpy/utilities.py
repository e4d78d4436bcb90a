"""``rclpy.utilities``: the default context and its state, the program's own arguments without
the ROS ones, the middleware's name, and rcl's timeouts in nanoseconds."""

from __future__ import annotations

import sys
from collections.abc import Sequence

from rclpy._context import Context, default_context
from rclpy._ros_args import parse_ros_args

RMW_IMPLEMENTATION = "rmw_zenoh_cpp"  # the lab speaks rmw_zenoh's wire format
S_TO_NS = 1_000_000_000


def get_default_context(*, shutting_down: bool = False) -> Context:
    """The process's context, the one ``rclpy.init()`` starts when given none."""
    return default_context


def remove_ros_args(args: Sequence[str] | None = None) -> list[str]:
    """``args`` (``sys.argv`` if None) without the ``--ros-args ... [--]`` parts."""
    return parse_ros_args(list(sys.argv if args is None else args)).rest


def ok(*, context: Context | None = None) -> bool:
    """Whether the context (the default one if None) is initialized and not shut down."""
    return (context or default_context).ok()


def shutdown(*, context: Context | None = None) -> None:
    """Shut the context down (RCLError if it is not running)."""
    (context or default_context).shutdown()


def try_shutdown(*, context: Context | None = None) -> None:
    """Shut the context down unless it already is."""
    ctx = context or default_context
    if ctx.ok():
        ctx.shutdown()


def get_rmw_implementation_identifier() -> str:
    return RMW_IMPLEMENTATION


def get_available_rmw_implementations() -> set[str]:
    return {RMW_IMPLEMENTATION}


def timeout_sec_to_nsec(timeout_sec: float | None) -> int:
    """Seconds as rcl's wait takes them: -1 (for ever) for None or a negative value."""
    if timeout_sec is None or timeout_sec < 0:
        return -1
    return int(float(timeout_sec) * S_TO_NS)


__all__ = [
    "get_available_rmw_implementations",
    "get_default_context",
    "get_rmw_implementation_identifier",
    "ok",
    "remove_ros_args",
    "shutdown",
    "timeout_sec_to_nsec",
    "try_shutdown",
]
