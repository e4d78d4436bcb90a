"""rclpy for the teleop lab: the ROS 2 Python client library's API, in the node's own process, joined
to the lab's graph over Zenoh in rmw_zenoh's wire format (so it also talks to a real ROS 2).

A student's node file runs unchanged: ``rclpy.init()``, a ``Node`` subclass, ``rclpy.spin(node)``,
``create_timer`` or ``create_rate`` with ``rate.sleep()``, and Ctrl-C as ``KeyboardInterrupt``.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from rclpy._context import Context, RCLError, default_context
from rclpy.executors import Executor, ExternalShutdownException, SingleThreadedExecutor
from rclpy.parameter import Parameter
from rclpy.task import Future
from rclpy.utilities import get_default_context, get_rmw_implementation_identifier, ok

_global_executor: Executor | None = None


class InitContextManager:
    """What ``rclpy.init()`` returns: ``with rclpy.init(args=args):`` shuts down on leaving, as
    Kilted's examples start; a plain ``rclpy.init()`` ignores it."""

    def __init__(self, context: Context) -> None:
        self.context = context

    def __enter__(self) -> InitContextManager:
        return self

    def __exit__(self, *_exc: object) -> None:
        try_shutdown(context=self.context)


def init(
    *,
    args: Sequence[str] | None = None,
    context: Context | None = None,
    domain_id: int | None = None,
    signal_handler_options: Any = None,
) -> InitContextManager:
    """Join the lab's graph (``--ros-args`` from ``args``, else from ``sys.argv``)."""
    ctx = context or default_context
    ctx.init(args, domain_id)
    return InitContextManager(ctx)


def shutdown(*, context: Context | None = None) -> None:
    global _global_executor
    ctx = context or default_context
    if _global_executor is not None and _global_executor.context is ctx:
        _global_executor.shutdown()
        _global_executor = None
    ctx.shutdown()


def try_shutdown(*, context: Context | None = None) -> None:
    """Shut down unless it already was (the handout's ``finally``)."""
    if (context or default_context).ok():
        shutdown(context=context)


def get_global_executor() -> Executor:
    global _global_executor
    if _global_executor is None or not _global_executor.context.ok():
        _global_executor = SingleThreadedExecutor()
    return _global_executor


def spin(node: Any, executor: Executor | None = None) -> None:
    """Run ``node``'s callbacks until shutdown; Ctrl-C raises KeyboardInterrupt, as in rclpy."""
    executor = executor or get_global_executor()
    try:
        executor.add_node(node)
        with executor._spinning():
            while executor.context.ok():
                executor.spin_once()
    finally:
        executor.remove_node(node)


def spin_once(node: Any, *, executor: Executor | None = None, timeout_sec: float | None = None) -> None:
    """Run one callback (or wait ``timeout_sec`` for one); the node is the executor's meanwhile."""
    executor = executor or get_global_executor()
    added = False
    try:
        added = executor.add_node(node)
        executor.spin_once(timeout_sec)
    finally:
        if added:
            executor.remove_node(node)


def spin_until_future_complete(
    node: Any, future: Future[Any], executor: Executor | None = None, timeout_sec: float | None = None
) -> None:
    executor = executor or get_global_executor()
    added = False
    try:
        added = executor.add_node(node)
        executor.spin_until_future_complete(future, timeout_sec)
    finally:
        if added:
            executor.remove_node(node)


def create_node(node_name: str, *, context: Context | None = None, **kwargs: Any) -> Any:
    """``rclpy.create_node('name')``: a plain Node, for code that composes instead of subclassing."""
    from rclpy.node import Node

    return Node(node_name, context=context, **kwargs)


__all__ = [
    "Context",
    "ExternalShutdownException",
    "Future",
    "InitContextManager",
    "Parameter",
    "RCLError",
    "create_node",
    "get_default_context",
    "get_global_executor",
    "get_rmw_implementation_identifier",
    "init",
    "ok",
    "shutdown",
    "spin",
    "spin_once",
    "spin_until_future_complete",
    "try_shutdown",
]
