"""velocity_controller_node: /uav/input/velocity → /uav/input/attitude (roll, pitch, yaw) + /uav/input/thrust.

Reads /uav/sensors/velocity (TwistStamped, world linear velocity) and /uav/sensors/attitude
(roll, pitch, yaw). Runs at 50 Hz. The velocity setpoint may come from the position controller
or straight from a student: non-finite or absurd ones are dropped with a warning.
"""

from __future__ import annotations

from node_runtime.bus import Node
from node_runtime.msgs import Float64, TwistStamped, Vector3
from server.packages.flightcontroller.setpoints import MAX_SPEED_SETPOINT_M_S, SetpointError, check_finite
from sim.control import VelocityController
from sim.quadrotor import QuadrotorParams

RATE_HZ = 50.0


class VelocityControllerNode(Node):
    def __init__(self) -> None:
        super().__init__("VelocityControllerNode")
        p = QuadrotorParams()
        self.controller = VelocityController(
            p.mass_kg, p.gravity_m_s2, drag_coeff_n_per_m_s2=p.drag_coeff_n_per_m_s2
        )
        self.velocity: tuple[float, float, float] | None = None
        self.euler: tuple[float, float, float] | None = None
        self.att_pub = self.create_publisher(Vector3, "/uav/input/attitude", 1, hand_over=True)
        self.thrust_pub = self.create_publisher(Float64, "/uav/input/thrust", 1, hand_over=True)
        self.create_subscription(Vector3, "/uav/input/velocity", self.on_setpoint, 1, read_only=True)
        self.create_subscription(TwistStamped, "/uav/sensors/velocity", self.on_velocity, 1, read_only=True)
        self.create_subscription(Vector3, "/uav/sensors/attitude", self.on_attitude, 1, read_only=True)
        self.create_timer(1.0 / RATE_HZ, self.tick)

    def on_setpoint(self, msg: Vector3) -> None:
        try:
            v = check_finite((msg.x, msg.y, msg.z), "/uav/input/velocity")
        except SetpointError as exc:
            self.get_logger().warning(f"velocity setpoint dropped: {exc}")
            return
        limited = tuple(min(max(c, -MAX_SPEED_SETPOINT_M_S), MAX_SPEED_SETPOINT_M_S) for c in v)
        self.controller.set_setpoint(limited, 0.0)

    def on_velocity(self, msg: TwistStamped) -> None:
        v = msg.twist.linear
        self.velocity = (v.x, v.y, v.z)

    def on_attitude(self, msg: Vector3) -> None:
        self.euler = (msg.x, msg.y, msg.z)

    def tick(self) -> None:
        if self.velocity is None or self.euler is None:
            return
        sp = self.controller.update(self.velocity, self.euler, 1.0 / RATE_HZ)
        self.att_pub.publish(Vector3(x=sp.roll_rad, y=sp.pitch_rad, z=sp.yaw_rad))
        self.thrust_pub.publish(Float64(data=sp.thrust_n))
