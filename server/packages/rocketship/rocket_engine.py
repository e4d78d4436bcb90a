"""RocketEngineNode: the sensed velocity is the last command plus N(0, 10) noise, published at 10 Hz."""

from __future__ import annotations

import numpy as np

from node_runtime.bus import Node
from node_runtime.bus.parameter_values import read_only
from node_runtime.msgs import Float64

SENSOR_NOISE_STD_M_S = 10.0


class RocketEngineNode(Node):
    def __init__(self) -> None:
        super().__init__("RocketEngineNode")
        seed = self.declare_parameter("seed", 0, read_only("the sensor noise's random seed")).value
        self.rng = np.random.default_rng(seed)
        self.sensor = 0.0
        self.create_subscription(Float64, "/cmd_vel", self.on_cmd_vel, 10)
        self.sensor_pub = self.create_publisher(Float64, "/sensor_vel", 1)
        self.timer = self.create_timer(0.1, self.publish_sensor)

    def on_cmd_vel(self, msg: Float64) -> None:
        # Noise is drawn once per command and held, as in the lab's engine.
        self.sensor = msg.data + float(self.rng.normal(0.0, SENSOR_NOISE_STD_M_S))

    def publish_sensor(self) -> None:
        self.sensor_pub.publish(Float64(data=self.sensor))
