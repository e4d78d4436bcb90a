"""KeyboardManagerNode for the drone: arrow keys on /keydown (and /keyup) → /uav/input/position.

The mapping fits the page's default camera, which looks from -y towards +y: RIGHT → +x (right
on screen), LEFT → -x, UP → +y (away from the viewer), DOWN → -y; Page Up / W → up (+z),
Page Down / S → down (-z). The setpoint starts at (0, 0, 3).

``mode`` (a parameter; it can be changed while running, like ``ros2 param set``):
- ``lab``: the handout's node: publishes its setpoint every tick at 20 Hz, reads the last key
  seen in each tick, 1 m per press (so it overrides anyone else publishing positions);
- ``adopt`` (default): 1 m per press, but it takes the latest setpoint seen on
  /uav/input/position as its own and publishes only when a key moves it, at once, so keys and
  REST or rqt-style publishing mix;
- ``hold``: hold to move: while keys are held the setpoint is kept ``hold_speed_m_s`` ×
  ``lead_s`` ahead of the drone (the position controller then flies at about that speed), and
  on release it is put where the drone will stop (``brake_s`` of its velocity ahead), so the
  drone stops promptly instead of chasing a setpoint far ahead.
"""

from __future__ import annotations

from typing import Any

from node_runtime.bus import Node, Parameter, Timer
from node_runtime.bus.parameter_values import double_range, read_only
from node_runtime.msgs import Key, PoseStamped, TwistStamped, Vector3
from node_runtime.msgs.generated.rcl_interfaces import ParameterDescriptor
from server.packages.flightcontroller.setpoints import clamp_to_arena

START_M = (0.0, 0.0, 3.0)
MODES = ("lab", "adopt", "hold")
DIRECTIONS: dict[int, tuple[float, float, float]] = {
    Key.KEY_RIGHT: (1.0, 0.0, 0.0),
    Key.KEY_LEFT: (-1.0, 0.0, 0.0),
    Key.KEY_UP: (0.0, 1.0, 0.0),
    Key.KEY_DOWN: (0.0, -1.0, 0.0),
    Key.KEY_PAGEUP: (0.0, 0.0, 1.0),
    Key.KEY_W: (0.0, 0.0, 1.0),
    Key.KEY_PAGEDOWN: (0.0, 0.0, -1.0),
    Key.KEY_S: (0.0, 0.0, -1.0),
}
HOLD_RATE_HZ = 50.0
# The parameters that may change while it runs: default, range, meaning.
LIMITS: dict[str, tuple[float, float, float, str]] = {
    "step_m": (1.0, 0.01, 10.0, "metres per key press"),
    "rate_hz": (20.0, 0.1, 1000.0, "publish rate in lab mode (Hz)"),
    "hold_speed_m_s": (2.0, 0.1, 10.0, "speed while a key is held, in hold mode (m/s)"),
    # 1 / the position controller's gain: lead × gain = speed
    "lead_s": (1.25, 0.05, 5.0, "how far ahead the setpoint leads, in hold mode (s)"),
    "brake_s": (0.55, 0.0, 2.0, "velocity × this is where a released key stops the drone (s)"),
}


class KeyboardManager(Node):
    def __init__(self) -> None:
        super().__init__("KeyboardManagerNode")
        self.declare_parameter("mode", "adopt", ParameterDescriptor(additional_constraints=" | ".join(MODES)))
        for name, (default, low, high, what) in LIMITS.items():
            self.declare_parameter(name, default, double_range(low, high, what))
        start_delay_s = float(
            self.declare_parameter("start_delay_s", 0.0, read_only("seconds before it starts")).value
        )
        self._check(self.get_parameters_dict())
        self.add_on_set_parameters_callback(self._on_set)
        self.position_pub = self.create_publisher(Vector3, "/uav/input/position", 1)
        self.keyboard_sub = self.create_subscription(Key, "/keydown", self.get_key, 1)
        self.create_subscription(Key, "/keyup", self.key_released, 10)
        self.create_subscription(Vector3, "/uav/input/position", self.adopt, 10)
        self.create_subscription(PoseStamped, "/uav/sensors/gps", self.on_gps, 1, read_only=True)
        self.create_subscription(TwistStamped, "/uav/sensors/velocity", self.on_velocity, 1, read_only=True)
        self.pos = Vector3(x=START_M[0], y=START_M[1], z=START_M[2])
        self.key_code = -1
        self.held: set[int] = set()
        self.drone_m: tuple[float, float, float] | None = None
        self.drone_v: tuple[float, float, float] = (0.0, 0.0, 0.0)
        self.timer: Timer | None = None
        self.started = False
        self._delay: Timer | None = None
        if start_delay_s > 0:  # the handout's node sleeps 10 s to let the simulator start
            self._delay = self.create_timer(start_delay_s, self.start)
        else:
            self.start()

    # -- parameters --------------------------------------------------------------
    @property
    def mode(self) -> str:
        return str(self.get_parameter("mode").value)

    def param(self, name: str) -> float:
        return float(self.get_parameter(name).value)

    @staticmethod
    def _check(values: dict[str, Any]) -> None:
        if values.get("mode", "adopt") not in MODES:
            raise ValueError(f"mode must be one of {', '.join(MODES)}, got {values['mode']!r}")
        for name, (_, lo, hi, _what) in LIMITS.items():
            if name in values and not lo <= float(values[name]) <= hi:
                raise ValueError(f"{name} must be in {lo:g}..{hi:g}, got {values[name]!r}")

    def _on_set(self, params: list[Parameter]) -> bool:
        self._check({p.name: p.value for p in params})
        return True

    def set_parameters(self, params: list[Parameter]) -> None:
        super().set_parameters(params)
        if any(p.name in ("mode", "rate_hz") for p in params):
            self.release_all_keys()
            self.start()

    # -- life --------------------------------------------------------------------
    def start(self) -> None:
        if self._delay is not None:
            self._delay.cancel()
            self._delay = None
        self._stop_timer()
        if self.mode == "lab":
            self.timer = self.create_timer(1.0 / self.param("rate_hz"), self.mainloop)
        self.started = True

    def _stop_timer(self) -> None:
        if self.timer is not None:
            self.destroy_timer(self.timer)
            self.timer = None

    # -- inputs ------------------------------------------------------------------
    def adopt(self, msg: Vector3) -> None:
        if self.mode != "lab":
            self.pos = msg

    def on_gps(self, msg: PoseStamped) -> None:
        p = msg.pose.position
        self.drone_m = (p.x, p.y, p.z)

    def on_velocity(self, msg: TwistStamped) -> None:
        v = msg.twist.linear
        self.drone_v = (v.x, v.y, v.z)

    def get_key(self, msg: Key) -> None:
        if self.mode == "lab":
            self.key_code = msg.code
        elif not self.started:
            return
        elif self.mode == "adopt":
            if self.step(msg.code):
                self.position_pub.publish(self.pos)
        elif msg.code in DIRECTIONS:
            self.held.add(msg.code)
            self.hold_tick()
            if self.timer is None:
                self.timer = self.create_timer(1.0 / HOLD_RATE_HZ, self.hold_tick)

    def key_released(self, msg: Key) -> None:
        if self.mode != "hold" or msg.code not in self.held:
            return
        self.held.discard(msg.code)
        if not self.held:
            self.release_all_keys()

    def release_all_keys(self) -> None:
        """Stop moving: the setpoint goes where the drone will come to rest."""
        was_holding = bool(self.held) or (self.mode == "hold" and self.timer is not None)
        self.held.clear()
        if self.mode == "hold":
            self._stop_timer()
        if was_holding and self.drone_m is not None:
            brake = self.param("brake_s")
            stop = tuple(p + v * brake for p, v in zip(self.drone_m, self.drone_v, strict=True))
            self._set(stop)
            self.position_pub.publish(self.pos)

    # -- outputs -----------------------------------------------------------------
    def _set(self, target: tuple[float, ...]) -> None:
        (x, y, z), _ = clamp_to_arena(target)
        self.pos = Vector3(x=x, y=y, z=z)

    def step(self, code: int) -> bool:
        """One press: move the setpoint ``step_m``; returns whether the key is a move key."""
        move = DIRECTIONS.get(code)
        if move is None or (self.mode == "lab" and move[2] != 0.0):
            return False  # the handout's node moves in x and y only
        d = self.param("step_m")
        self._set((self.pos.x + move[0] * d, self.pos.y + move[1] * d, self.pos.z + move[2] * d))
        return True

    def hold_tick(self) -> None:
        """While keys are held: a setpoint ``lead`` ahead of the drone, along the held keys."""
        if not self.held:
            return
        direction = [sum(DIRECTIONS[c][i] for c in self.held) for i in range(3)]
        lead = self.param("hold_speed_m_s") * self.param("lead_s")
        norm = max(sum(c * c for c in direction) ** 0.5, 1e-9)
        base = self.drone_m if self.drone_m is not None else (self.pos.x, self.pos.y, self.pos.z)
        # Axes not being driven keep their setpoint, so moving sideways does not change height.
        current = (self.pos.x, self.pos.y, self.pos.z)
        target = [base[i] + direction[i] / norm * lead if direction[i] else current[i] for i in range(3)]
        self._set(tuple(target))
        self.position_pub.publish(self.pos)

    def mainloop(self) -> None:
        self.position_pub.publish(self.pos)
        self.step(self.key_code)
        if self.key_code != -1:
            self.key_code = -1
