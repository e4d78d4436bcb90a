"""What one drone (QuadrotorSim) and a batch (QuadrotorBatch) share besides the dynamics: the physics
rate's bound, process-noise blocks, command checks and clamps, and the state a reset leaves a drone in."""

from __future__ import annotations

import math

import numpy as np

from sim.quadrotor.dynamics import Vector
from sim.quadrotor.params import QuadrotorParams
from sim.quadrotor.rotation import euler_sxyz_to_quat
from sim.quadrotor.state import Command, MotorSpeedCommand, RateThrustCommand
from sim.types import FloatArray, FloatsLike

MIN_PHYSICS_RATE_HZ = 500.0
NOISE_BLOCK = 1024
"""Steps of process noise a drone draws from its generator per call."""


def physics_step_s(physics_rate_hz: float) -> float:
    """1 / physics_rate_hz, or ValueError below MIN_PHYSICS_RATE_HZ."""
    if not (math.isfinite(physics_rate_hz) and physics_rate_hz >= MIN_PHYSICS_RATE_HZ):
        raise ValueError(f"physics_rate_hz must be >= {MIN_PHYSICS_RATE_HZ}, got {physics_rate_hz}")
    return 1.0 / float(physics_rate_hz)


def noise_scale(p: QuadrotorParams, dt_s: float) -> FloatArray:
    """Per-step standard deviations of the process noise: linear x, y, z then angular x, y, z."""
    lin = math.sqrt(p.linear_process_noise_m2_s3 / dt_s)
    ang = math.sqrt(p.angular_process_noise_rad2_s3 / dt_s)
    return np.array([lin, lin, lin, ang, ang, ang])


def draw_noise(rng: np.random.Generator, scale: FloatArray) -> FloatArray:
    """The next NOISE_BLOCK steps of one drone's process noise, (NOISE_BLOCK, 6), in draw order."""
    return rng.standard_normal((NOISE_BLOCK, 6)) * scale


def clamp_rate_thrust(p: QuadrotorParams, command: RateThrustCommand) -> tuple[list[float], float]:
    """Body rates clamped to +-max_rate_command and thrust to [0, max thrust]; ValueError if not finite."""
    # Re-validated here because a frozen dataclass can still be forced to hold NaN.
    checked = RateThrustCommand(command.body_rates_rad_s, command.thrust_n)
    limit = p.max_rate_command_rad_s
    rates = [min(max(r, -limit), limit) for r in checked.body_rates_rad_s]
    return rates, min(max(checked.thrust_n, 0.0), p.max_thrust_n)


def clamp_motor_speeds(p: QuadrotorParams, command: MotorSpeedCommand) -> tuple[float, float, float, float]:
    """Rotor speeds clamped to [0, max_rotor_speed]; ValueError if not finite."""
    checked = MotorSpeedCommand(command.rotor_speeds_rad_s)
    top = p.max_rotor_speed_rad_s
    c1, c2, c3, c4 = (min(max(w, 0.0), top) for w in checked.rotor_speeds_rad_s)
    return c1, c2, c3, c4


def not_a_command(command: object) -> TypeError:
    return TypeError(f"expected RateThrustCommand or MotorSpeedCommand, got {type(command).__name__}")


def rest_state(p: QuadrotorParams, position_m: FloatsLike, yaw_rad: float, rotors_at_hover: bool) -> Vector:
    """The flat state of a drone at rest at position_m (z clamped to >= 0), level, facing yaw_rad."""
    px, py, pz = (float(v) for v in position_m)
    if not all(math.isfinite(v) for v in (px, py, pz, yaw_rad)):
        raise ValueError("reset position_m and yaw_rad must be finite")
    rotor = p.hover_rotor_speed_rad_s if rotors_at_hover else 0.0
    q = euler_sxyz_to_quat(0.0, 0.0, yaw_rad)
    return [px, py, max(pz, 0.0), 0.0, 0.0, 0.0, *q, 0.0, 0.0, 0.0, rotor, rotor, rotor, rotor]


def rest_command(p: QuadrotorParams, rotors_at_hover: bool) -> Command:
    """The command a reset holds: no rates, and the weight's thrust if the rotors start at hover."""
    return RateThrustCommand((0.0, 0.0, 0.0), p.mass_kg * p.gravity_m_s2 if rotors_at_hover else 0.0)
