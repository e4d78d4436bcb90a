"""flightgoggles_uav_dynamics: rotor physics behind the lab's topics.

In: /uav/input/rateThrust (TwistStamped: angular = body rates rad/s, linear.z = thrust N).
Out, at ``publish_rate_hz`` (100 by default): /uav/sensors/gps (PoseStamped, frame ``world``),
/uav/sensors/velocity (TwistStamped: linear = world velocity m/s, angular = body rates rad/s),
/uav/sensors/attitude (Vector3: roll, pitch, yaw rad), and the pose on /tf (``world`` →
``uav/imu``, as FlightGoggles broadcasts it, for Foxglove's 3D panel). The physics steps at
``physics_rate_hz`` (1000) and follows the bus clock, so sim time is real time while the world
keeps up. A tick that comes late flies at most one flight-controller period on the last command
and skips the rest, so a world starved of CPU flies slower than real time, not open-loop.
"""

from __future__ import annotations

import numpy as np

from node_runtime.bus import Node
from node_runtime.bus.parameter_values import double_range, read_only
from node_runtime.msgs import (
    Header,
    Point,
    Pose,
    PoseStamped,
    Quaternion,
    TFMessage,
    Transform,
    TransformStamped,
    Twist,
    TwistStamped,
    Vector3,
)
from server.peripherals.devices.shared_physics import QUADROTOR_MAX_CATCH_UP_S, SharedQuadrotorPhysics
from sim.quadrotor import Drone, QuadrotorSim, RateThrustCommand
from sim.quadrotor.rotation import quat_to_euler_sxyz
from sim.quadrotor.state import Kinematics

BODY_FRAME = "uav/imu"  # FlightGoggles' name for the body frame


class UavDynamicsNode(Node):
    def __init__(self) -> None:
        super().__init__("flightgoggles_uav_dynamics")
        rate_hz = float(
            self.declare_parameter(
                "publish_rate_hz",
                100.0,
                double_range(10.0, 1000.0, "rate of the sensor topics and /tf (Hz)", fixed=True),
            ).value
        )
        physics_hz = float(
            self.declare_parameter(
                "physics_rate_hz", 1000.0, read_only("rate of the physics steps (Hz)")
            ).value
        )
        noise = bool(self.declare_parameter("noise", True, read_only("sensor noise on")).value)
        seed = int(self.declare_parameter("seed", 0, read_only("the sim's random seed")).value)
        if not 10.0 <= rate_hz <= 1000.0:
            raise ValueError(f"publish_rate_hz must be in 10..1000, got {rate_hz}")
        # On a class server every world's drone steps in one shared batch (server/peripherals/devices/
        # shared_physics.py); alone, the drone has a QuadrotorSim of its own. Same model either way.
        self.shared: SharedQuadrotorPhysics | None = self.bus.devices.get("quadrotor_physics")
        # A late tick flies at most this long on the last command (a slower publish rate ticks
        # further apart than the controllers' period, so it may fly up to two of its own ticks).
        self.max_catch_up_s = max(QUADROTOR_MAX_CATCH_UP_S, 2.0 / rate_hz)
        if self.shared is not None and (
            self.shared.physics_rate_hz != physics_hz or self.shared.max_catch_up_s < self.max_catch_up_s
        ):
            self.shared = None  # another physics rate or tick than the class's: this world steps its own
        self.sim: QuadrotorSim | Drone = (
            self.shared.add(seed, noise)
            if self.shared is not None
            else QuadrotorSim(rng=np.random.default_rng(seed), noise=noise, physics_rate_hz=physics_hz)
        )
        self.gps_pub = self.create_publisher(PoseStamped, "/uav/sensors/gps", 10, hand_over=True)
        self.vel_pub = self.create_publisher(TwistStamped, "/uav/sensors/velocity", 10, hand_over=True)
        self.att_pub = self.create_publisher(Vector3, "/uav/sensors/attitude", 10, hand_over=True)
        self.tf_pub = self.create_publisher(TFMessage, "/tf", 100, hand_over=True)
        self.create_subscription(TwistStamped, "/uav/input/rateThrust", self.on_command, 1, read_only=True)
        self._last_s = self.bus.clock.now()
        self.create_timer(1.0 / rate_hz, self.tick)
        self.publish_state(self.sim.kinematics())

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
            self.sim.advance(min(max(now - self._last_s, 0.0), self.max_catch_up_s))
        self._last_s = now
        self.publish_state(self.sim.kinematics())

    def destroy_node(self) -> bool:
        if self.shared is not None and not isinstance(self.sim, QuadrotorSim) and self.state != "destroyed":
            self.sim.remove()  # the world resets or leaves: its drone leaves the shared batch
        return super().destroy_node()

    def publish_state(self, k: Kinematics) -> None:
        # Each message is built whole from plain floats (no state snapshot's arrays, no default
        # parts made and then replaced): this runs 100 times a second in every world of a class server.
        # One header for the three: the publishers hand their messages over, and nothing changes a
        # message after it is published (a subscriber that may gets a copy of its own).
        header = Header(stamp=self.get_clock().now().to_msg(), frame_id="world")
        x, y, z, vx, vy, vz, qw, qx, qy, qz, wx, wy, wz = k
        gps = PoseStamped(
            header=header,
            pose=Pose(position=Point(x=x, y=y, z=z), orientation=Quaternion(x=qx, y=qy, z=qz, w=qw)),
        )
        self.gps_pub.publish(gps)
        vel = TwistStamped(
            header=header,
            twist=Twist(linear=Vector3(x=vx, y=vy, z=vz), angular=Vector3(x=wx, y=wy, z=wz)),
        )
        self.vel_pub.publish(vel)
        roll, pitch, yaw = quat_to_euler_sxyz((qw, qx, qy, qz))
        self.att_pub.publish(Vector3(x=roll, y=pitch, z=yaw))
        tf = TransformStamped(
            header=header,
            child_frame_id=BODY_FRAME,
            transform=Transform(
                translation=Vector3(x=x, y=y, z=z), rotation=Quaternion(x=qx, y=qy, z=qz, w=qw)
            ),
        )
        self.tf_pub.publish(TFMessage(transforms=[tf]))
