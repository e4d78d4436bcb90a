"""What arrives from outside the app (Foxglove's Publish panel, a rosbridge client) is checked as
the REST API checks it (node_runtime/limits.py): a setpoint with NaN, infinity or an absurd value
never reaches a node."""

from __future__ import annotations

from typing import Any

from node_runtime.limits import check_finite_json, check_topic_limits
from node_runtime.msgs import Message


def check_inbound(topic: str, message: Message, as_json: Any = None) -> None:
    """Raise ValueError if ``message`` (and the JSON it came as, if any) must not go on ``topic``."""
    if as_json is not None:
        check_finite_json(as_json)
    check_topic_limits(topic, message)
