"""The controller cascade of one drone at one fixed rate, and ClosedLoop: one QuadrotorSim under it.

Each control tick samples the true state (no estimator), runs position (unless a velocity
setpoint was given directly) -> velocity -> angle, and holds the resulting rateThrust
command for the whole tick while the physics steps at its own rate. Cascade alone drives a
drone of a QuadrotorBatch the same way: command(drone.state) each tick, then step the batch.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from sim.control.cascade import (
    AngleController,
    AngleGains,
    PositionController,
    PositionGains,
    VelocityController,
    VelocityGains,
)
from sim.quadrotor.params import QuadrotorParams
from sim.quadrotor.sim import QuadrotorSim
from sim.quadrotor.state import QuadrotorState, RateThrustCommand, as_finite_floats
from sim.types import FloatsLike


@dataclass(frozen=True)
class CascadeGains:
    """Gains of the three controllers; the defaults are the shipped tuning."""

    position: PositionGains = field(default_factory=PositionGains)
    velocity: VelocityGains = field(default_factory=VelocityGains)
    angle: AngleGains = field(default_factory=AngleGains)


class Cascade:
    """Position -> velocity -> angle for one drone: set a setpoint, then command(state) once per control tick."""

    def __init__(
        self, params: QuadrotorParams, gains: CascadeGains | None = None, control_rate_hz: float = 50.0
    ):
        if not control_rate_hz > 0:
            raise ValueError(f"control_rate_hz must be > 0, got {control_rate_hz}")
        gains = gains if gains is not None else CascadeGains()
        self.control_dt_s = 1.0 / control_rate_hz
        self.position = PositionController(gains.position)
        p = params
        self.velocity = VelocityController(p.mass_kg, p.gravity_m_s2, gains.velocity, p.drag_coeff_n_per_m_s2)
        self.angle = AngleController(gains.angle)
        self._velocity_mode = False
        self._yaw_rad = 0.0

    def set_position_setpoint(self, position_m: FloatsLike, yaw_rad: float = 0.0) -> None:
        """Fly to position_m (m, world) facing yaw_rad; the position controller drives the velocity."""
        (yaw,) = as_finite_floats("yaw_rad", (yaw_rad,), 1)
        self.position.set_setpoint(position_m)
        self._yaw_rad = yaw
        self._velocity_mode = False

    def set_velocity_setpoint(self, velocity_m_s: FloatsLike, yaw_rad: float = 0.0) -> None:
        """Track velocity_m_s (m/s, world) directly, bypassing the position controller."""
        self.velocity.set_setpoint(velocity_m_s, yaw_rad)
        self._velocity_mode = True

    def command(self, state: QuadrotorState) -> RateThrustCommand:
        """The rateThrust command to hold for the next control period, from the sampled state."""
        dt = self.control_dt_s
        if not self._velocity_mode:
            self.velocity.set_setpoint(self.position.update(state.position_m, dt), self._yaw_rad)
        self.angle.set_setpoint(self.velocity.update(state.velocity_m_s, state.euler_sxyz_rad, dt))
        return self.angle.update(state.euler_sxyz_rad, dt)


class ClosedLoop:
    """The sim plus the cascade. Call set_position_setpoint or set_velocity_setpoint, then run()."""

    def __init__(self, sim: QuadrotorSim, gains: CascadeGains | None = None, control_rate_hz: float = 50.0):
        if not control_rate_hz > 0 or control_rate_hz > sim.physics_rate_hz:
            raise ValueError(f"control_rate_hz must be in (0, {sim.physics_rate_hz}], got {control_rate_hz}")
        self.sim = sim
        self.cascade = Cascade(sim.params, gains, control_rate_hz)
        self.control_dt_s = self.cascade.control_dt_s
        self.position, self.velocity, self.angle = (
            self.cascade.position,
            self.cascade.velocity,
            self.cascade.angle,
        )
        self.set_position_setpoint = self.cascade.set_position_setpoint
        self.set_velocity_setpoint = self.cascade.set_velocity_setpoint

    def tick(self) -> QuadrotorState:
        """One control period: sample, control, advance the physics. Returns the sampled state."""
        state = self.sim.state
        self.sim.set_command(self.cascade.command(state))
        self.sim.advance(self.control_dt_s)
        return state

    def run(self, duration_s: float) -> list[QuadrotorState]:
        """Tick for duration_s (rounded to whole control periods); returns the state after each tick."""
        ticks = round(duration_s / self.control_dt_s)
        samples = []
        for _ in range(ticks):
            self.tick()
            samples.append(self.sim.state)
        return samples
