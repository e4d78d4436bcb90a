"""flightgoggles_uav_dynamics: rotor physics behind the lab's topics.

In: /uav/input/rateThrust (TwistStamped: angular = body rates rad/s, linear.z = thrust N).
Out, at ``publish_rate_hz`` (100 by default): /uav/sensors/gps (PoseStamped, frame ``world``),
/uav/sensors/velocity (TwistStamped: linear = world velocity m/s, angular = body rates rad/s),
/uav/sensors/attitude (Vector3: roll, pitch, yaw rad), and the pose on /tf (``world`` →
``uav/imu``, as FlightGoggles broadcasts it, for Foxglove's 3D panel). The physics steps at
``physics_rate_hz`` (1000) and follows the bus clock, so sim time is real time.
"""

from __future__ import annotations

import numpy as np

from server.bus import Node
from server.devices.shared_physics import SharedQuadrotorPhysics
from server.msgs import PoseStamped, TFMessage, TransformStamped, TwistStamped, Vector3
from sim.quadrotor import Drone, QuadrotorSim, QuadrotorState, RateThrustCommand

BODY_FRAME = "uav/imu"  # FlightGoggles' name for the body frame
MAX_CATCH_UP_S = 0.1  # after a stall, the sim skips ahead rather than running a burst of steps


class UavDynamicsNode(Node):
    def __init__(self) -> None:
        super().__init__("flightgoggles_uav_dynamics")
        rate_hz = float(self.declare_parameter("publish_rate_hz", 100.0).value)
        physics_hz = float(self.declare_parameter("physics_rate_hz", 1000.0).value)
        noise = bool(self.declare_parameter("noise", True).value)
        seed = int(self.declare_parameter("seed", 0).value)
        if not 10.0 <= rate_hz <= 1000.0:
            raise ValueError(f"publish_rate_hz must be in 10..1000, got {rate_hz}")
        # On a class server every world's drone steps in one shared batch (server/devices/
        # shared_physics.py); alone, the drone has a QuadrotorSim of its own. Same model either way.
        self.shared: SharedQuadrotorPhysics | None = self.bus.devices.get("quadrotor_physics")
        if self.shared is not None and self.shared.physics_rate_hz != physics_hz:
            self.shared = None  # another physics rate than the class's: this world steps its own
        self.sim: QuadrotorSim | Drone = (
            self.shared.add(seed, noise)
            if self.shared is not None
            else QuadrotorSim(rng=np.random.default_rng(seed), noise=noise, physics_rate_hz=physics_hz)
        )
        self.gps_pub = self.create_publisher(PoseStamped, "/uav/sensors/gps", 10)
        self.vel_pub = self.create_publisher(TwistStamped, "/uav/sensors/velocity", 10)
        self.att_pub = self.create_publisher(Vector3, "/uav/sensors/attitude", 10)
        self.tf_pub = self.create_publisher(TFMessage, "/tf", 100)
        self.create_subscription(TwistStamped, "/uav/input/rateThrust", self.on_command, 1)
        self._last_s = self.bus.clock.now()
        self.create_timer(1.0 / rate_hz, self.tick)
        self.publish_state(self.sim.state)

    def on_command(self, msg: TwistStamped) -> None:
        a = msg.twist.angular
        if self.shared is not None:
            # The steps up to now were flown on the old command whichever world's tick runs them:
            # a drone's flight then does not depend on the other worlds' timers.
            self.shared.advance_to(self.bus.clock.now())
        try:
            self.sim.set_command(RateThrustCommand((a.x, a.y, a.z), msg.twist.linear.z))
        except ValueError as exc:
            self.get_logger().warning(f"rateThrust dropped: {exc}")

    def tick(self) -> None:
        now = self.bus.clock.now()
        if self.shared is not None:
            self.shared.advance_to(now)
        elif isinstance(self.sim, QuadrotorSim):
            self.sim.advance(min(max(now - self._last_s, 0.0), MAX_CATCH_UP_S))
        self._last_s = now
        self.publish_state(self.sim.state)

    def destroy_node(self) -> bool:
        if self.shared is not None and not isinstance(self.sim, QuadrotorSim) and self.state != "destroyed":
            self.sim.remove()  # the world resets or leaves: its drone leaves the shared batch
        return super().destroy_node()

    def publish_state(self, s: QuadrotorState) -> None:
        stamp = self.get_clock().now().to_msg()
        gps = PoseStamped()
        gps.header.stamp, gps.header.frame_id = stamp, "world"
        p, q = gps.pose.position, gps.pose.orientation
        p.x, p.y, p.z = s.position_m.tolist()
        q.w, q.x, q.y, q.z = s.attitude_wxyz.tolist()
        self.gps_pub.publish(gps)
        vel = TwistStamped()
        vel.header.stamp, vel.header.frame_id = stamp, "world"
        lin, ang = vel.twist.linear, vel.twist.angular
        lin.x, lin.y, lin.z = s.velocity_m_s.tolist()
        ang.x, ang.y, ang.z = s.body_rates_rad_s.tolist()
        self.vel_pub.publish(vel)
        roll, pitch, yaw = s.euler_sxyz_rad
        self.att_pub.publish(Vector3(x=roll, y=pitch, z=yaw))
        tf = TransformStamped(child_frame_id=BODY_FRAME)
        tf.header.stamp, tf.header.frame_id = stamp, "world"
        t, r = tf.transform.translation, tf.transform.rotation
        t.x, t.y, t.z = p.x, p.y, p.z
        r.w, r.x, r.y, r.z = q.w, q.x, q.y, q.z
        self.tf_pub.publish(TFMessage(transforms=[tf]))
