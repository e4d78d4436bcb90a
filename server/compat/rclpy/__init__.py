"""rclpy's entry points for lab code loaded by the app: the app owns the context and the executor."""

from __future__ import annotations

from typing import Any

_SPIN_MESSAGE = (
    "in the teleop lab the server spins every node: start this node with a launch file or "
    "`python -m server run PKG EXEC` instead of running the file itself"
)


def init(args: Any = None, context: Any = None) -> None:
    """Nothing to do: the app has already made the bus."""


def ok(context: Any = None) -> bool:
    return True


def shutdown(context: Any = None) -> None:
    """Nothing to do: the app shuts the bus down."""


def try_shutdown(context: Any = None) -> None:
    """Nothing to do: the app shuts the bus down."""


def spin(node: Any, executor: Any = None) -> None:
    raise RuntimeError(_SPIN_MESSAGE)


def spin_once(node: Any, executor: Any = None, timeout_sec: float | None = None) -> None:
    raise RuntimeError(_SPIN_MESSAGE)
