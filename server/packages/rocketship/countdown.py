"""CountDownNode: after a start delay, publishes 10, 9, ..., 0 on /countdown at 1 Hz, then stays quiet."""

from __future__ import annotations

from node_runtime.bus import Node, Timer
from node_runtime.bus.parameter_values import read_only
from node_runtime.msgs import Int64

MAX_START_DELAY_S = 3600.0


class CountDownNode(Node):
    def __init__(self) -> None:
        super().__init__("CountDownNode")
        delay = self.declare_parameter("start_delay_s", 5.0, read_only("seconds before lift-off")).value
        if (
            isinstance(delay, bool)
            or not isinstance(delay, (int, float))
            or not 0 <= delay <= MAX_START_DELAY_S
        ):
            raise ValueError(
                f"start_delay_s must be a number of seconds in 0..{MAX_START_DELAY_S}, got {delay!r}"
            )
        self.countdown_pub = self.create_publisher(Int64, "/countdown", 1000)
        self.remaining = 10
        self.timer: Timer | None = None
        if delay > 0:
            self.delay_timer = self.create_timer(float(delay), self.start)
        else:
            self.start()

    def start(self) -> None:
        if self.timer is not None:
            return
        if getattr(self, "delay_timer", None) is not None:
            self.delay_timer.cancel()
        self.timer = self.create_timer(1.0, self.tick)
        self.tick()

    def tick(self) -> None:
        if self.remaining < 0:
            return
        self.countdown_pub.publish(Int64(data=self.remaining))
        self.remaining -= 1
