"""Respawn with backoff: how long to wait before restarting a crashed node, and when to stop.

A node that crashes soon after it started (a *fast failure*) waits twice as long each time,
up to a cap; after ``max_fast_failures`` in a row the launcher gives up and leaves it crashed.
A node that ran for ``healthy_after_s`` before crashing starts again from the base delay. The
policy reads time from an injected clock, so tests step it; the launcher (and later a process
supervisor) only asks it ``crashed()`` and tells it ``started()``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Literal

from node_runtime.bus import Clock

RespawnState = Literal["running", "waiting", "gave up"]


@dataclass(frozen=True)
class RespawnPolicy:
    base_delay_s: float = 0.5
    max_delay_s: float = 30.0
    healthy_after_s: float = 10.0  # a crash after this long is not a fast failure
    max_fast_failures: int = 5

    def __post_init__(self) -> None:
        if (
            not 0 < self.base_delay_s <= self.max_delay_s
            or self.healthy_after_s <= 0
            or self.max_fast_failures < 1
        ):
            raise ValueError(f"an inconsistent respawn policy: {self}")


class RespawnBackoff:
    """One launched node's respawn history under a ``RespawnPolicy``, on ``clock``."""

    def __init__(self, policy: RespawnPolicy, clock: Clock) -> None:
        self.policy = policy
        self.clock = clock
        self.started_at_s = clock.now()
        self.respawns = 0
        self.fast_failures = 0
        self.state: RespawnState = "running"
        self.next_at_s: float | None = None

    def started(self) -> None:
        """The node is running (again)."""
        self.started_at_s = self.clock.now()
        self.state, self.next_at_s = "running", None

    def crashed(self, minimum_delay_s: float = 0.0) -> float | None:
        """The node crashed: the delay before respawning it (at least ``minimum_delay_s``, the
        launch file's respawn_delay), or None when it is time to give up."""
        now = self.clock.now()
        if now - self.started_at_s >= self.policy.healthy_after_s:
            self.fast_failures = 0
        self.fast_failures += 1
        if self.fast_failures > self.policy.max_fast_failures:
            self.state, self.next_at_s = "gave up", None
            return None
        backoff = self.policy.base_delay_s * 2.0 ** (self.fast_failures - 1)
        delay = max(minimum_delay_s, min(backoff, self.policy.max_delay_s))
        self.respawns += 1
        self.state, self.next_at_s = "waiting", now + delay
        return delay

    def describe(self) -> dict[str, Any]:
        """What the node list shows: state, respawns so far, fast failures in a row, seconds to the next try."""
        next_in_s = None if self.next_at_s is None else max(0.0, self.next_at_s - self.clock.now())
        return {
            "state": self.state,
            "respawns": self.respawns,
            "fast_failures": self.fast_failures,
            "next_in_s": next_in_s,
        }
