"""SimpleSimNode: the lab's kinematic sim at 20 Hz: /uav/input/velocity in, /uav/sensors/gps out."""

from __future__ import annotations

from typing import Literal, cast

import numpy as np

from server.bus import Node
from server.msgs import PoseStamped, Vector3
from sim.quadrotor import GpsReading, SimpleSim, SimpleSimParams


class SimpleSimNode(Node):
    def __init__(self) -> None:
        super().__init__("SimpleSimNode")
        seed = int(self.declare_parameter("seed", 0).value)
        noise = bool(self.declare_parameter("noise", True).value)
        wobble = str(self.declare_parameter("wobble_noise", "lab").value)
        if wobble not in ("lab", "fixed"):
            raise ValueError(f"wobble_noise must be lab or fixed, got {wobble!r}")
        params = SimpleSimParams(wobble_noise=cast(Literal["lab", "fixed"], wobble))
        self.sim = SimpleSim(params, rng=np.random.default_rng(seed), noise=noise)
        self.gps_pub = self.create_publisher(PoseStamped, "/uav/sensors/gps", 10, hand_over=True)
        self.create_subscription(Vector3, "/uav/input/velocity", self.on_velocity, 10, read_only=True)
        self.create_timer(self.sim.dt_s, self.tick)

    def on_velocity(self, msg: Vector3) -> None:
        try:
            self.sim.set_velocity_command((msg.x, msg.y, msg.z))
        except ValueError as exc:
            self.get_logger().warning(f"velocity command dropped: {exc}")

    def tick(self) -> None:
        self.publish_gps(self.sim.tick())

    def publish_gps(self, reading: GpsReading) -> None:
        gps = PoseStamped()
        gps.header.stamp, gps.header.frame_id = self.get_clock().now().to_msg(), "world"
        p, q = gps.pose.position, gps.pose.orientation
        p.x, p.y, p.z = reading.position_m
        q.w, q.x, q.y, q.z = reading.attitude_wxyz
        self.gps_pub.publish(gps)
