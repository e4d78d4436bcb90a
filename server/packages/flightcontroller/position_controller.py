"""position_controller_node: /uav/input/position (Vector3) + /uav/sensors/gps → /uav/input/velocity.

Two modes, chosen by the ``mode`` parameter:
- ``cascade`` (default): the retuned P law with speed limits, 50 Hz, feeding the velocity controller;
- ``lab``: the Fall 2025 node exactly: three PIDs (Kp=1, Ki=0, Kd=0) at 100 Hz, unsaturated,
  feeding simple_sim.
Setpoints that are NaN, infinite or absurd are dropped with a warning; setpoints outside the
arena are clamped to it with a warning.
"""

from __future__ import annotations

from node_runtime.bus import Node, Parameter, Timer
from node_runtime.bus.parameter_values import double_range, read_only
from node_runtime.msgs import PoseStamped, Vector3
from server.packages.flightcontroller.setpoints import SetpointError, check_finite, clamp_to_arena
from sim.control import LAB_PID_DT_S, LabPositionController, PositionController

DEFAULT_SETPOINT_M = (0.0, 0.0, 3.0)
CASCADE_RATE_HZ = 50.0
MAX_GAIN = 100.0


class PositionControllerNode(Node):
    def __init__(self) -> None:
        super().__init__("PositionControllerNode")
        self.mode = self.declare_parameter("mode", "cascade", read_only("cascade or lab")).value
        if self.mode not in ("cascade", "lab"):
            raise ValueError(f"mode must be 'cascade' or 'lab', got {self.mode!r}")
        start_delay_s = float(
            self.declare_parameter("start_delay_s", 0.0, read_only("seconds before it starts")).value
        )
        if self.mode == "lab":  # its PID's gains, which a set changes at once
            kp = float(
                self.declare_parameter("gains.p", 1.0, double_range(0.0, MAX_GAIN, "P gain (1/s)")).value
            )
            ki = float(
                self.declare_parameter("gains.i", 0.0, double_range(0.0, MAX_GAIN, "I gain (1/s²)")).value
            )
            kd = float(self.declare_parameter("gains.d", 0.0, double_range(0.0, MAX_GAIN, "D gain")).value)
            self.controller: LabPositionController | PositionController = LabPositionController(kp, ki, kd)
            self.period_s = LAB_PID_DT_S
        else:
            self.controller = PositionController(setpoint_m=DEFAULT_SETPOINT_M)
            self.period_s = 1.0 / CASCADE_RATE_HZ
        self.position: tuple[float, float, float] | None = None
        self._last_clamped: tuple[float, float, float] | None = None
        self.vel_pub = self.create_publisher(Vector3, "/uav/input/velocity", 1, hand_over=True)
        self.create_subscription(Vector3, "/uav/input/position", self.on_setpoint, 10, read_only=True)
        self.create_subscription(PoseStamped, "/uav/sensors/gps", self.on_gps, 1, read_only=True)
        self.timer: Timer | None = None
        if start_delay_s > 0:  # the lab's node sleeps 5 s before it starts
            self._delay = self.create_timer(start_delay_s, self.start)
        else:
            self.start()

    def set_parameters(self, params: list[Parameter]) -> None:
        super().set_parameters(params)
        if isinstance(self.controller, LabPositionController):
            kp, ki, kd = (float(self.get_parameter(f"gains.{g}").value) for g in "pid")
            for pid in self.controller.pids:
                pid.kp, pid.ki, pid.kd = kp, ki, kd

    @property
    def setpoint_m(self) -> tuple[float, ...]:
        return tuple(self.controller.setpoint_m)

    def start(self) -> None:
        if getattr(self, "_delay", None) is not None:
            self._delay.cancel()
        if self.timer is None:
            self.timer = self.create_timer(self.period_s, self.tick)

    def on_setpoint(self, msg: Vector3) -> None:
        try:
            target = check_finite((msg.x, msg.y, msg.z), "/uav/input/position")
        except SetpointError as exc:
            self.get_logger().warning(f"setpoint dropped: {exc}")
            return
        clamped, was_outside = clamp_to_arena(target)
        if was_outside and clamped != self._last_clamped:  # once per new setpoint, not at 50 Hz
            self.get_logger().warning(f"setpoint {target} is outside the arena; clamped to {clamped}")
        self._last_clamped = clamped
        self.controller.set_setpoint(clamped)
        if self.mode == "cascade" and self.timer is not None:
            # A P law has no state to disturb: answer a new setpoint now rather than at the next
            # tick, which takes up to 20 ms off every key press's response.
            self.tick()

    def on_gps(self, msg: PoseStamped) -> None:
        p = msg.pose.position
        self.position = (p.x, p.y, p.z)

    def tick(self) -> None:
        if self.position is None:
            return
        vx, vy, vz = self.controller.update(self.position, self.period_s)
        self.vel_pub.publish(Vector3(x=vx, y=vy, z=vz))
