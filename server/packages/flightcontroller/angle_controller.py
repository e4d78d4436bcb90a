"""angle_controller_node: /uav/input/attitude + /uav/input/thrust → /uav/input/rateThrust.

rateThrust is a TwistStamped as in the ROS 2 port: ``angular`` = body rates (rad/s),
``linear.z`` = collective thrust (N). Roll and pitch setpoints are clamped to ±0.5 rad.
"""

from __future__ import annotations

from node_runtime.bus import Node
from node_runtime.msgs import Float64, TwistStamped, Vector3
from sim.control import AngleController, AttitudeThrustSetpoint

RATE_HZ = 50.0


class AngleControllerNode(Node):
    def __init__(self) -> None:
        super().__init__("AngleControllerNode")
        self.controller = AngleController()
        self.attitude_sp = (0.0, 0.0, 0.0)
        self.thrust_n = 0.0
        self.euler: tuple[float, float, float] | None = None
        self.cmd_pub = self.create_publisher(TwistStamped, "/uav/input/rateThrust", 1, hand_over=True)
        self.create_subscription(Vector3, "/uav/input/attitude", self.on_attitude_sp, 1, read_only=True)
        self.create_subscription(Float64, "/uav/input/thrust", self.on_thrust, 1, read_only=True)
        self.create_subscription(Vector3, "/uav/sensors/attitude", self.on_attitude, 1, read_only=True)
        self.create_timer(1.0 / RATE_HZ, self.tick)

    def on_attitude_sp(self, msg: Vector3) -> None:
        self.attitude_sp = (msg.x, msg.y, msg.z)

    def on_thrust(self, msg: Float64) -> None:
        self.thrust_n = msg.data

    def on_attitude(self, msg: Vector3) -> None:
        self.euler = (msg.x, msg.y, msg.z)

    def tick(self) -> None:
        if self.euler is None:
            return
        roll, pitch, yaw = self.attitude_sp
        self.controller.set_setpoint(AttitudeThrustSetpoint(roll, pitch, yaw, self.thrust_n))
        try:
            cmd = self.controller.update(self.euler, 1.0 / RATE_HZ)
        except ValueError as exc:  # a non-finite setpoint from a hand-published message
            self.get_logger().warning(f"attitude setpoint dropped: {exc}")
            return
        out = TwistStamped()
        out.header.stamp = self.get_clock().now().to_msg()
        out.header.frame_id = "uav/imu"
        out.twist.angular.x, out.twist.angular.y, out.twist.angular.z = cmd.body_rates_rad_s
        out.twist.linear.z = cmd.thrust_n
        self.cmd_pub.publish(out)
