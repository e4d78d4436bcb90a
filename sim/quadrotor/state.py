"""Typed commands and state snapshots of the quadrotor simulator."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from sim.quadrotor.rotation import quat_to_euler_sxyz
from sim.types import FloatArray, FloatsLike


def as_finite_floats(name: str, values: FloatsLike, length: int) -> tuple[float, ...]:
    """The values as a tuple of floats, or ValueError naming the field."""
    try:
        floats = tuple(map(float, values))
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be {length} numbers") from exc
    if len(floats) != length:
        raise ValueError(f"{name} must have {length} components, got {len(floats)}")
    if not all(map(math.isfinite, floats)):
        raise ValueError(f"{name} must be finite, got {floats}")
    return floats


@dataclass(frozen=True)
class RateThrustCommand:
    """FlightGoggles' rateThrust input: body rates (rad/s, body frame) and collective thrust (N).

    Values outside the vehicle's range are accepted here and clamped by the simulator.
    """

    body_rates_rad_s: tuple[float, float, float] = (0.0, 0.0, 0.0)
    thrust_n: float = 0.0

    def __post_init__(self) -> None:
        rates = as_finite_floats("body_rates_rad_s", self.body_rates_rad_s, 3)
        (thrust,) = as_finite_floats("thrust_n", (self.thrust_n,), 1)
        object.__setattr__(self, "body_rates_rad_s", rates)
        object.__setattr__(self, "thrust_n", thrust)


@dataclass(frozen=True)
class MotorSpeedCommand:
    """Direct rotor-speed command (rad/s) for motors 1-4, bypassing the inner rate loop."""

    rotor_speeds_rad_s: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0)

    def __post_init__(self) -> None:
        speeds = as_finite_floats("rotor_speeds_rad_s", self.rotor_speeds_rad_s, 4)
        object.__setattr__(self, "rotor_speeds_rad_s", speeds)


Command = RateThrustCommand | MotorSpeedCommand


Kinematics = tuple[float, float, float, float, float, float, float, float, float, float, float, float, float]
"""One drone's motion as plain floats, in this order: position (m, world), velocity (m/s, world),
attitude (w, x, y, z; body to world), body rates (rad/s, body). What a sim's ``kinematics()``
returns: the same values as its ``state`` without building its read-only arrays, for code that
reads them at every tick (the dynamics node publishes them 100 times a second in every world)."""


def _frozen_array(values: FloatsLike) -> FloatArray:
    array = np.array(values, dtype=float)
    array.flags.writeable = False
    return array


@dataclass(frozen=True)
class QuadrotorState:
    """One snapshot of the vehicle. Arrays are read-only copies.

    position_m and velocity_m_s are in the world frame (z up); attitude_wxyz rotates body
    to world; body_rates_rad_s are in the body frame; on_ground is True while in contact.
    """

    time_s: float
    position_m: FloatArray
    velocity_m_s: FloatArray
    attitude_wxyz: FloatArray
    body_rates_rad_s: FloatArray
    rotor_speeds_rad_s: FloatArray
    on_ground: bool
    euler_sxyz_rad: tuple[float, float, float] = field(init=False)

    def __post_init__(self) -> None:
        for name in ("position_m", "velocity_m_s", "attitude_wxyz", "body_rates_rad_s", "rotor_speeds_rad_s"):
            object.__setattr__(self, name, _frozen_array(getattr(self, name)))
        object.__setattr__(self, "euler_sxyz_rad", quat_to_euler_sxyz(self.attitude_wxyz))

    @property
    def roll_rad(self) -> float:
        return self.euler_sxyz_rad[0]

    @property
    def pitch_rad(self) -> float:
        return self.euler_sxyz_rad[1]

    @property
    def yaw_rad(self) -> float:
        return self.euler_sxyz_rad[2]
