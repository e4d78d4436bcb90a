"""``rclpy.wait_for_message.wait_for_message``: the next message of a topic, without spinning.

As rclpy's, it waits on a subscription of its own and runs no other callback: it takes in what
the transport has brought for every topic (those messages wait in their queues for the next
spin) and looks at its own subscription's.
"""

from __future__ import annotations

import contextlib
import threading
import time
from typing import Any

from rclpy.qos import QoSProfile

POLL_S = 0.005  # how often it looks again while nothing has come


def wait_for_message(
    msg_type: type[Any],
    node: Any,
    topic: str,
    *,
    qos_profile: QoSProfile | int = 1,
    time_to_wait: float = -1,
) -> tuple[bool, Any]:
    """``(True, msg)`` once a message comes; ``(False, None)`` after ``time_to_wait`` seconds
    (negative: no limit) or when the context shuts down."""
    got: list[Any] = []
    sub = node.create_subscription(msg_type, topic, got.append, qos_profile=qos_profile)
    context = node.context
    bus = node._bus
    end = None if time_to_wait < 0 else time.monotonic() + time_to_wait
    idle = threading.Event()
    try:
        while context.ok():
            with bus.lock if bus.lock is not None else contextlib.nullcontext():
                for poll in list(bus.pollers):
                    poll()
                if not got and sub.queue:
                    got.append(sub.queue.popleft())
            if got:
                return True, got[0]
            if end is not None and time.monotonic() >= end:
                break
            idle.wait(POLL_S)
    finally:
        if not sub.destroyed:
            node.destroy_subscription(sub)
    return False, None


__all__ = ["wait_for_message"]
