"""The lab's kinematic simple_sim (lab reference §3.3): velocity in, GPS pose out, at 20 Hz.

Reproduced as the lab runs it: no gravity, no ground, explicit Euler, velocity tracked
within one tick except for a 5 m/s per-tick cap on each axis, and a decorative wobble
whose phase noise has sigma = phase/10 (the lab's bug; wobble_noise="fixed" uses
sigma = wobble_tilt/10 as a later student fork does).

SimpleSim is one drone in plain floats; SimpleSimBatch (sim.quadrotor.simple_batch) ticks many
together, each bit for bit as a SimpleSim with the same seed and commands.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np

from sim.quadrotor.fixed_step import FixedStepClock
from sim.quadrotor.rotation import euler_sxyz_to_quat
from sim.quadrotor.state import as_finite_floats
from sim.types import FloatsLike

WobbleNoise = Literal["lab", "fixed"]


@dataclass(frozen=True)
class SimpleSimParams:
    """Constants of SimpleSimNode."""

    rate_hz: float = 20.0
    max_velocity_step_m_s: float = 5.0
    """Largest velocity change per tick on each axis (m/s), i.e. 100 m/s^2 at 20 Hz."""
    gps_noise_m: float = 0.01
    """Standard deviation of the GPS position noise per axis (m)."""
    wobble_speed: float = 1.0
    """Wobble phase advance per second of sim time (rad/s)."""
    wobble_tilt_rad: float = math.pi / 16
    wobble_noise: WobbleNoise = "lab"

    def __post_init__(self) -> None:
        for name in ("rate_hz", "max_velocity_step_m_s", "wobble_speed", "wobble_tilt_rad"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0):
                raise ValueError(f"SimpleSimParams.{name} must be positive, got {value}")
        if not (math.isfinite(self.gps_noise_m) and self.gps_noise_m >= 0):
            raise ValueError(f"SimpleSimParams.gps_noise_m must be >= 0, got {self.gps_noise_m}")
        if self.wobble_noise not in ("lab", "fixed"):
            raise ValueError(
                f"SimpleSimParams.wobble_noise must be 'lab' or 'fixed', got {self.wobble_noise!r}"
            )


@dataclass(frozen=True)
class GpsReading:
    """/uav/sensors/gps: noisy position (m, world) and noise-free attitude (w, x, y, z)."""

    time_s: float
    position_m: tuple[float, float, float]
    attitude_wxyz: tuple[float, float, float, float]


@dataclass(frozen=True)
class SimpleSimState:
    """True kinematic state (no noise)."""

    time_s: float
    position_m: tuple[float, float, float]
    velocity_m_s: tuple[float, float, float]
    attitude_wxyz: tuple[float, float, float, float]
    wobble_phase_rad: float


class SimpleSim:
    """SimpleSimNode without ROS: set_velocity_command() then tick() at rate_hz (or advance())."""

    def __init__(
        self,
        params: SimpleSimParams | None = None,
        *,
        rng: np.random.Generator | None = None,
        noise: bool = True,
    ) -> None:
        if noise and rng is None:
            raise ValueError("noise=True needs a seeded numpy.random.Generator as rng")
        self.params = params if params is not None else SimpleSimParams()
        self.dt_s = 1.0 / self.params.rate_hz
        self._rng = rng
        self._noise = noise
        self._pos = [0.0, 0.0, 0.0]
        self._vel = [0.0, 0.0, 0.0]
        self._cmd = (0.0, 0.0, 0.0)
        self._wobble = 0.0
        self._att = (1.0, 0.0, 0.0, 0.0)
        self._ticks = 0
        self._clock = FixedStepClock(self.params.rate_hz)
        self.gps = GpsReading(0.0, (0.0, 0.0, 0.0), self._att)
        """The latest GPS reading; before the first tick, the noise-free origin."""

    @property
    def time_s(self) -> float:
        return self._ticks * self.dt_s

    @property
    def state(self) -> SimpleSimState:
        p, v = self._pos, self._vel
        return SimpleSimState(self.time_s, (p[0], p[1], p[2]), (v[0], v[1], v[2]), self._att, self._wobble)

    def set_velocity_command(self, velocity_m_s: FloatsLike) -> None:
        """The latest /uav/input/velocity (m/s, world). ValueError on non-finite input."""
        vx, vy, vz = as_finite_floats("velocity_m_s", velocity_m_s, 3)
        self._cmd = (vx, vy, vz)

    def advance(self, duration_s: float) -> list[GpsReading]:
        """Tick for duration_s, carrying the remainder; returns the GPS readings produced."""
        return [self.tick() for _ in range(self._clock.steps_for(duration_s))]

    def tick(self) -> GpsReading:
        """One 1/rate_hz step of the lab's timer callback; returns the published GPS reading."""
        p, dt = self.params, self.dt_s
        cap = p.max_velocity_step_m_s
        steps = [c - v for c, v in zip(self._cmd, self._vel, strict=True)]
        steps = [d if abs(d) <= cap else d * (cap / abs(d)) for d in steps]
        self._wobble += dt * (p.wobble_speed + self._normal(self._wobble_sigma()))
        tilt = p.wobble_tilt_rad
        self._att = euler_sxyz_to_quat(tilt * math.cos(self._wobble), tilt * math.sin(self._wobble), 0.0)
        self._vel = [v + d for v, d in zip(self._vel, steps, strict=True)]
        self._pos = [x + v * dt for x, v in zip(self._pos, self._vel, strict=True)]
        self._ticks += 1
        gps = [x + self._normal(p.gps_noise_m) for x in self._pos]
        self.gps = GpsReading(self.time_s, (gps[0], gps[1], gps[2]), self._att)
        return self.gps

    def _wobble_sigma(self) -> float:
        if self.params.wobble_noise == "lab":
            return abs(self._wobble) / 10.0  # the lab's bug: noise grows with the phase
        return self.params.wobble_tilt_rad / 10.0

    def _normal(self, sigma: float) -> float:
        if not self._noise or self._rng is None or sigma == 0.0:
            return 0.0
        return float(self._rng.normal(0.0, sigma))
