"""SimpleSimNode: the lab's kinematic sim at 20 Hz: /uav/input/velocity in, /uav/sensors/gps out.

On a class server every world's drone ticks in one shared batch (server/peripherals/devices/shared_physics.py,
SharedSimpleSim); alone, the drone has a SimpleSim of its own and ticks on this node's timer.
"""

from __future__ import annotations

from typing import Literal, cast

import numpy as np

from node_runtime.bus import Node
from node_runtime.bus.parameter_values import read_only
from node_runtime.msgs import PoseStamped, Vector3
from server.peripherals.devices.shared_physics import SharedSimpleSim
from sim.quadrotor import GpsReading, SimpleDrone, SimpleSim, SimpleSimParams


class SimpleSimNode(Node):
    def __init__(self) -> None:
        super().__init__("SimpleSimNode")
        seed = int(self.declare_parameter("seed", 0, read_only("the sim's random seed")).value)
        noise = bool(self.declare_parameter("noise", True, read_only("sensor noise on")).value)
        wobble = str(self.declare_parameter("wobble_noise", "lab", read_only("lab or fixed")).value)
        if wobble not in ("lab", "fixed"):
            raise ValueError(f"wobble_noise must be lab or fixed, got {wobble!r}")
        params = SimpleSimParams(wobble_noise=cast(Literal["lab", "fixed"], wobble))
        self.shared: SharedSimpleSim | None = self.bus.devices.get("simple_sim_physics")
        if self.shared is not None and self.shared.params != params:
            self.shared = None  # other constants than the class's batch: this world ticks its own
        self.sim: SimpleSim | SimpleDrone = (
            self.shared.add(seed, noise)
            if self.shared is not None
            else SimpleSim(params, rng=np.random.default_rng(seed), noise=noise)
        )
        self.gps_pub = self.create_publisher(PoseStamped, "/uav/sensors/gps", 10, hand_over=True)
        self.create_subscription(Vector3, "/uav/input/velocity", self.on_velocity, 10, read_only=True)
        self.create_timer(1.0 / params.rate_hz, self.tick)

    def on_velocity(self, msg: Vector3) -> None:
        if self.shared is not None:
            # The ticks up to now ran on the old command whichever world's timer runs them.
            self.shared.advance_to(self.bus.clock.now())
        try:
            self.sim.set_velocity_command((msg.x, msg.y, msg.z))
        except ValueError as exc:
            self.get_logger().warning(f"velocity command dropped: {exc}")

    def tick(self) -> None:
        if isinstance(self.sim, SimpleSim):
            self.publish_gps(self.sim.tick())
            return
        assert self.shared is not None
        self.shared.advance_to(self.bus.clock.now())
        self.publish_gps(self.sim.gps)  # the batch's newest reading of this drone, as a 20 Hz sensor

    def destroy_node(self) -> bool:
        if isinstance(self.sim, SimpleDrone) and self.state != "destroyed":
            self.sim.remove()  # the world resets or leaves: its drone leaves the shared batch
        return super().destroy_node()

    def publish_gps(self, reading: GpsReading) -> None:
        gps = PoseStamped()
        gps.header.stamp, gps.header.frame_id = self.get_clock().now().to_msg(), "world"
        p, q = gps.pose.position, gps.pose.orientation
        p.x, p.y, p.z = reading.position_m
        q.w, q.x, q.y, q.z = reading.attitude_wxyz
        self.gps_pub.publish(gps)
