"""QuadrotorSim: fixed-step RK4 physics of one quadrotor with its on-board rate loop, in plain floats."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from sim.quadrotor.dynamics import NO_NOISE, RigidBodyModel, Vector, normalize_quaternion, rk4_step
from sim.quadrotor.fixed_step import FixedStepClock
from sim.quadrotor.ground import GroundContact
from sim.quadrotor.params import QuadrotorParams
from sim.quadrotor.rate_control import RateLoop
from sim.quadrotor.state import Command, Kinematics, MotorSpeedCommand, QuadrotorState, RateThrustCommand
from sim.quadrotor.vehicle import (
    MIN_PHYSICS_RATE_HZ,
    clamp_motor_speeds,
    clamp_rate_thrust,
    draw_noise,
    noise_scale,
    not_a_command,
    physics_step_s,
    rest_command,
    rest_state,
)
from sim.types import FloatsLike

__all__ = ["MIN_PHYSICS_RATE_HZ", "QuadrotorSim"]


class QuadrotorSim:
    """One quadrotor stepped at a fixed physics rate; time advances only through advance()/step().

    The input is either a RateThrustCommand (tracked by the on-board rate loop at physics
    rate, like FlightGoggles' rateThrust) or a MotorSpeedCommand. Commands are held until
    replaced. The vehicle starts on the ground at the given position, level, rotors at rest
    unless rotors_at_hover. A drone of a QuadrotorBatch with the same seed and commands steps
    bit for bit as this does.
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
        self.dt_s = physics_step_s(physics_rate_hz)
        if noise and rng is None:
            raise ValueError("noise=True needs a seeded numpy.random.Generator as rng")
        self.params = params if params is not None else QuadrotorParams()
        self.physics_rate_hz = float(physics_rate_hz)
        self._rng = rng if noise else None
        self._noise_scale = noise_scale(self.params, self.dt_s)
        self._model = RigidBodyModel(self.params)
        self._ground = GroundContact(self.params, self.dt_s)
        self._rate_loop = RateLoop(self.params, self.dt_s)
        self._per_thrust = self._rate_loop.gains.per_thrust
        self._max_rate = self.params.max_body_rate_rad_s
        self._clock = FixedStepClock(self.physics_rate_hz)
        self.reset(initial_position_m, initial_yaw_rad, rotors_at_hover)

    def reset(
        self,
        position_m: FloatsLike = (0.0, 0.0, 0.0),
        yaw_rad: float = 0.0,
        rotors_at_hover: bool = False,
    ) -> None:
        """Put the vehicle at rest at position_m (z clamped to >= 0), level, clock at 0, command cleared."""
        self._s: Vector = rest_state(self.params, position_m, yaw_rad, rotors_at_hover)
        self._on_ground = self._s[2] <= 0.0
        self._steps = 0
        self._clock.reset()
        self._noise: list[list[float]] = []
        self._rate_loop.reset()
        self.set_command(rest_command(self.params, rotors_at_hover))

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

    def kinematics(self) -> Kinematics:
        """Position, velocity, attitude and body rates as floats (see Kinematics)."""
        s = self._s
        return (s[0], s[1], s[2], s[3], s[4], s[5], s[6], s[7], s[8], s[9], s[10], s[11], s[12])

    def set_command(self, command: Command) -> None:
        """Hold a new input until the next call. Raises ValueError (and keeps the old one) if invalid."""
        if isinstance(command, RateThrustCommand):
            rates, thrust = clamp_rate_thrust(self.params, command)
            self._rates_cmd = (rates[0], rates[1], rates[2])
            self._base = thrust * self._per_thrust  # the thrust's share of the squared rotor speeds
            self._motor_cmd: tuple[float, float, float, float] | None = None
        elif isinstance(command, MotorSpeedCommand):
            self._motor_cmd = clamp_motor_speeds(self.params, command)
        else:
            raise not_a_command(command)

    def advance(self, duration_s: float) -> int:
        """Step for duration_s of simulated time; the part short of a whole step carries over. Returns steps taken."""
        return self._clock.run(duration_s, self.step)

    def step(self) -> None:
        """One physics step: rate loop and mixer, RK4, renormalise, rate clamp, ground contact."""
        s, dt = self._s, self.dt_s
        if self._motor_cmd is not None:
            rotor_cmd = self._motor_cmd
        else:
            rotor_cmd = self._rate_loop.rotor_commands(s[10:13], self._rates_cmd, self._base)
        new = rk4_step(s, rotor_cmd, self._model, self._next_noise(), dt)
        normalize_quaternion(new)
        top, bottom = self._max_rate, -self._max_rate
        w1, w2, w3 = new[10], new[11], new[12]  # each min(max(w, bottom), top), written out
        new[10] = bottom if bottom > w1 else (top if top < w1 else w1)
        new[11] = bottom if bottom > w2 else (top if top < w2 else w2)
        new[12] = bottom if bottom > w3 else (top if top < w3 else w3)
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
        if self._rng is None:
            return NO_NOISE
        if not self._noise:
            self._noise = draw_noise(self._rng, self._noise_scale).tolist()[::-1]  # popped from the end
        return self._noise.pop()
