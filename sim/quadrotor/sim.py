"""QuadrotorSim: fixed-step RK4 physics of one quadrotor with its on-board rate loop."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from sim.quadrotor.dynamics import NO_NOISE, RigidBodyModel, Vector, normalize_quaternion, rk4_step
from sim.quadrotor.ground import GroundContact
from sim.quadrotor.params import QuadrotorParams
from sim.quadrotor.rate_control import RateLoop
from sim.quadrotor.rotation import euler_sxyz_to_quat
from sim.quadrotor.state import Command, MotorSpeedCommand, QuadrotorState, RateThrustCommand
from sim.types import FloatsLike

MIN_PHYSICS_RATE_HZ = 500.0
_NOISE_BATCH = 1024  # steps of process noise drawn per generator call


class QuadrotorSim:
    """One quadrotor stepped at a fixed physics rate; time advances only through advance()/step().

    The input is either a RateThrustCommand (tracked by the on-board rate loop at physics
    rate, like FlightGoggles' rateThrust) or a MotorSpeedCommand. Commands are held until
    replaced. The vehicle starts on the ground at the given position, level, rotors at rest
    unless rotors_at_hover.
    """

    def __init__(
        self,
        params: QuadrotorParams | None = None,
        *,
        rng: np.random.Generator | None = None,
        noise: bool = True,
        physics_rate_hz: float = 1000.0,
        initial_position_m: FloatsLike = (0.0, 0.0, 0.0),
        initial_yaw_rad: float = 0.0,
        rotors_at_hover: bool = False,
    ) -> None:
        if not (math.isfinite(physics_rate_hz) and physics_rate_hz >= MIN_PHYSICS_RATE_HZ):
            raise ValueError(f"physics_rate_hz must be >= {MIN_PHYSICS_RATE_HZ}, got {physics_rate_hz}")
        if noise and rng is None:
            raise ValueError("noise=True needs a seeded numpy.random.Generator as rng")
        self.params = params if params is not None else QuadrotorParams()
        self.physics_rate_hz = float(physics_rate_hz)
        self.dt_s = 1.0 / self.physics_rate_hz
        self._rng = rng
        self._noise_scale = (
            (math.sqrt(self.params.linear_process_noise_m2_s3 / self.dt_s),) * 3
            + (math.sqrt(self.params.angular_process_noise_rad2_s3 / self.dt_s),) * 3
            if noise
            else None
        )
        self._model = RigidBodyModel(self.params)
        self._ground = GroundContact(self.params, self.dt_s)
        self._rate_loop = RateLoop(self.params)
        self._max_rate = self.params.max_body_rate_rad_s
        self.reset(initial_position_m, initial_yaw_rad, rotors_at_hover)

    def reset(
        self,
        position_m: FloatsLike = (0.0, 0.0, 0.0),
        yaw_rad: float = 0.0,
        rotors_at_hover: bool = False,
    ) -> None:
        """Put the vehicle at rest at position_m (z clamped to >= 0), level, clock at 0, command cleared."""
        px, py, pz = (float(v) for v in position_m)
        if not all(math.isfinite(v) for v in (px, py, pz, yaw_rad)):
            raise ValueError("reset position_m and yaw_rad must be finite")
        rotor = self.params.hover_rotor_speed_rad_s if rotors_at_hover else 0.0
        q = euler_sxyz_to_quat(0.0, 0.0, yaw_rad)
        self._s: Vector = [px, py, max(pz, 0.0), 0.0, 0.0, 0.0, *q, 0.0, 0.0, 0.0, rotor, rotor, rotor, rotor]
        self._on_ground = self._s[2] <= 0.0
        self._steps = 0
        self._remainder_s = 0.0
        self._noise: list[list[float]] = []
        self._rate_loop.reset()
        hover_thrust = self.params.mass_kg * self.params.gravity_m_s2 if rotors_at_hover else 0.0
        self.set_command(RateThrustCommand((0.0, 0.0, 0.0), hover_thrust))

    @property
    def time_s(self) -> float:
        """Simulated time since reset (s): steps taken times dt."""
        return self._steps * self.dt_s

    @property
    def state(self) -> QuadrotorState:
        """A frozen copy of the current state."""
        s = self._s
        return QuadrotorState(
            time_s=self.time_s,
            position_m=np.array(s[0:3]),
            velocity_m_s=np.array(s[3:6]),
            attitude_wxyz=np.array(s[6:10]),
            body_rates_rad_s=np.array(s[10:13]),
            rotor_speeds_rad_s=np.array(s[13:17]),
            on_ground=self._on_ground,
        )

    def set_command(self, command: Command) -> None:
        """Hold a new input until the next call. Raises ValueError (and keeps the old one) if invalid."""
        if isinstance(command, RateThrustCommand):
            # Re-validated here because a frozen dataclass can still be forced to hold NaN.
            checked = RateThrustCommand(command.body_rates_rad_s, command.thrust_n)
            limit = self.params.max_rate_command_rad_s
            rates = tuple(min(max(r, -limit), limit) for r in checked.body_rates_rad_s)
            self._rates_cmd: tuple[float, float, float] = rates  # type: ignore[assignment]
            self._thrust_cmd = min(max(checked.thrust_n, 0.0), self.params.max_thrust_n)
            self._motor_cmd: tuple[float, float, float, float] | None = None
        elif isinstance(command, MotorSpeedCommand):
            checked_m = MotorSpeedCommand(command.rotor_speeds_rad_s)
            top = self.params.max_rotor_speed_rad_s
            c1, c2, c3, c4 = (min(max(w, 0.0), top) for w in checked_m.rotor_speeds_rad_s)
            self._motor_cmd = (c1, c2, c3, c4)
        else:
            raise TypeError(f"expected RateThrustCommand or MotorSpeedCommand, got {type(command).__name__}")

    def advance(self, duration_s: float) -> int:
        """Step for duration_s of simulated time; the part short of a whole step carries over. Returns steps taken."""
        if not (math.isfinite(duration_s) and duration_s >= 0.0):
            raise ValueError(f"duration_s must be finite and >= 0, got {duration_s}")
        total = self._remainder_s + duration_s
        # The epsilon absorbs rounding so that 0.02 s at 1 kHz is 20 steps, not 19.
        n = math.floor(total * self.physics_rate_hz + 1e-6)
        self._remainder_s = max(0.0, total - n * self.dt_s)
        for _ in range(n):
            self.step()
        return n

    def step(self) -> None:
        """One physics step: rate loop and mixer, RK4, renormalise, ground contact."""
        s, dt = self._s, self.dt_s
        if self._motor_cmd is not None:
            rotor_cmd = self._motor_cmd
        else:
            rotor_cmd = self._rate_loop.rotor_commands(s[10:13], self._rates_cmd, self._thrust_cmd, dt)
        new = rk4_step(s, rotor_cmd, self._model, self._next_noise(), dt)
        normalize_quaternion(new)
        top = self._max_rate
        new[10], new[11], new[12] = (min(max(w, -top), top) for w in new[10:13])
        contact, resting = self._ground.apply(new)
        if resting:
            self._rate_loop.reset_integral()
        if not math.isfinite(math.fsum(new)):
            # Cannot happen with clamped inputs; refuse to store a corrupt state if it ever does.
            raise FloatingPointError(f"non-finite quadrotor state after step at t={self.time_s:.3f} s")
        self._s = new
        self._on_ground = contact
        self._steps += 1

    def _next_noise(self) -> Sequence[float]:
        if self._noise_scale is None or self._rng is None:
            return NO_NOISE
        if not self._noise:
            draws = self._rng.standard_normal((_NOISE_BATCH, 6)) * np.array(self._noise_scale)
            self._noise = draws.tolist()[::-1]  # popped from the end, so reverse to keep draw order
        return self._noise.pop()
