"""What arrives from outside the app (Foxglove's Publish panel, a rosbridge client) is checked as
the REST API checks it: a setpoint with NaN, infinity or an absurd value never reaches a node."""

from __future__ import annotations

from server.lab import TOPIC_GUARDS
from server.msgs import Message


def check_inbound(topic: str, message: Message) -> None:
    """Raise ValueError if ``message`` must not be published on ``topic``."""
    guard = TOPIC_GUARDS.get(topic)
    if guard is not None and type(message) is guard[0]:
        guard[1](message)
