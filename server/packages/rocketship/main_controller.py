"""MainControllerNode: launches at the end of the countdown and ramps /cmd_vel along a tanh curve.

Faithful to the lab's C++ node: the same log lines, an abort before launch is permanent, an
abort after launch logs "Abort Failed", and after a successful abort /cmd_vel is never published.
"""

from __future__ import annotations

import math

import numpy as np

from node_runtime.bus import Node
from node_runtime.msgs import Bool, Float64, Int64

HALF_TOP_SPEED_M_S = 842.0  # v = 842 (tanh(c) + 1): 0 → 1684 m/s, about a Falcon 9's top speed
C_START = np.float32(-5.0)  # a float in the original, so it is stepped in float32 here too
C_STEP = np.float32(0.01)


def commanded_velocity(c: np.float32) -> float:
    return (math.tanh(float(c)) + 1.0) * HALF_TOP_SPEED_M_S


class MainControllerNode(Node):
    def __init__(self) -> None:
        super().__init__("MainControllerNode")
        self.launch = False
        self.abort_mission = False
        self.c = C_START
        self.cmd_pub = self.create_publisher(Float64, "/cmd_vel", 1000)
        self.create_subscription(Int64, "/countdown", self.on_countdown, 1000)
        self.create_subscription(Bool, "/abort_takeoff", self.on_abort, 1000)
        self.timer = self.create_timer(0.1, self.main_loop)
        self.get_logger().info("Rocket Ready for Countdown")

    def on_countdown(self, msg: Int64) -> None:
        if self.abort_mission:
            return
        self.get_logger().info(f"Countdown: {msg.data}s")
        if msg.data <= 0:
            self.launch = True

    def on_abort(self, msg: Bool) -> None:
        if not msg.data:
            return
        if not self.launch:
            self.get_logger().info("Abort Abort Abort!!!")
            self.abort_mission = True
        else:
            self.get_logger().info("Abort Failed")
            self.abort_mission = False

    def main_loop(self) -> None:
        if not self.launch or self.abort_mission:
            return
        v = commanded_velocity(self.c)
        self.c = np.float32(self.c + C_STEP)
        self.get_logger().info(f"Requested Velocity: {v:.6f}m/s")
        self.cmd_pub.publish(Float64(data=v))
