"""PressureSensorNode: /uav/sensors/gps altitude → /uav/sensors/pressure (mbar) at 10 Hz, as the lab's.

Publishes the value computed on the previous tick (so the first message is 0.0), with
U(-1e-5, 1e-5) noise, like the original.
"""

from __future__ import annotations

import numpy as np

from node_runtime.bus import Node
from node_runtime.bus.parameter_values import read_only
from node_runtime.msgs import Float64, PoseStamped

_POLY = (-3.86423e-22, 8.56075e-17, -7.58614e-12, 3.36124e-7, -0.00744645, 65.987)  # h^5 .. h^0


def pressure_mbar(altitude_m: float) -> float:
    """The lab's barometric formula: 1013.250 mbar at 0 m, 1012.049 at 10 m."""
    h = altitude_m
    poly = 0.0
    for c in _POLY:  # Horner's rule, as numpy.polyval, on plain floats: this runs 10 times a second per world
        poly = poly * h + c
    return float((44307.7 - h) ** (12145 / 47571) * poly)


class PressureSensorNode(Node):
    def __init__(self) -> None:
        super().__init__("PressureSensorNode")
        seed = self.declare_parameter("seed", 0, read_only("the sensor noise's random seed"))
        self.rng = np.random.default_rng(int(seed.value))
        self.altitude_m = 0.0
        self.pending = 0.0
        self.pub = self.create_publisher(Float64, "/uav/sensors/pressure", 1, hand_over=True)
        self.create_subscription(PoseStamped, "/uav/sensors/gps", self.on_gps, 1, read_only=True)
        self.create_timer(0.1, self.tick)

    def on_gps(self, msg: PoseStamped) -> None:
        self.altitude_m = msg.pose.position.z

    def tick(self) -> None:
        self.pub.publish(Float64(data=self.pending))
        self.pending = pressure_mbar(self.altitude_m) + float(self.rng.uniform(-1e-5, 1e-5))
