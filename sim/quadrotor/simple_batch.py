"""SimpleSimBatch: the lab's kinematic simple_sim (see sim.quadrotor.simple_sim) for n drones at once.

Each tick is SimpleSim.tick for every drone: the arithmetic is one elementwise numpy pass over
all of them, with the same operations in the same order as SimpleSim's plain floats; each
drone's noise comes from its own generator, drawn in the lab's order, and its wobble attitude
from math.cos/math.sin, whose results cannot depend on the other drones. So a drone ticks bit
for bit as a SimpleSim with the same seed and commands would. For one drone, SimpleSim is the
faster choice.
"""

from __future__ import annotations

import math

import numpy as np

from sim.quadrotor.fixed_step import FixedStepClock
from sim.quadrotor.rotation import euler_sxyz_to_quat
from sim.quadrotor.simple_sim import GpsReading, SimpleSimParams, SimpleSimState
from sim.quadrotor.slots import DroneHandle, SlotTable
from sim.quadrotor.state import as_finite_floats
from sim.types import FloatsLike

_POS, _VEL, _CMD, _WOBBLE, _GPS, _ATT = slice(0, 3), slice(3, 6), slice(6, 9), 9, slice(10, 13), slice(13, 17)
_ROWS = 17


class SimpleSimBatch:
    """SimpleSimNode for n drones without ROS: set each drone's velocity command, then tick() all at rate_hz."""

    def __init__(self, params: SimpleSimParams | None = None) -> None:
        self.params = params if params is not None else SimpleSimParams()
        self.dt_s = 1.0 / self.params.rate_hz
        self._clock = FixedStepClock(self.params.rate_hz)
        self._slots = SlotTable({"floats": ((_ROWS,), float)})
        self._ticks = 0

    def __len__(self) -> int:
        return len(self._slots)

    @property
    def drones(self) -> tuple[SimpleDrone, ...]:
        """Handles of the drones in the batch, oldest first."""
        return tuple(SimpleDrone(self, i) for i in self._slots.ids)

    def add(self, *, rng: np.random.Generator | None = None, noise: bool = True) -> SimpleDrone:
        """A new drone at rest at the origin; with noise, rng must be its own seeded generator."""
        if noise and rng is None:
            raise ValueError("noise=True needs a seeded numpy.random.Generator as rng")
        drone_id = self._slots.add(rng if noise else None, self._ticks)
        self.reset(drone_id)
        return SimpleDrone(self, drone_id)

    def remove(self, drone_id: int) -> None:
        """Take a drone out; the others keep their state and their replay. DroneRemovedError if unknown."""
        self._slots.remove(drone_id)

    def reset(self, drone_id: int) -> None:
        """One drone back at rest at the origin, level, command zero, its clock at 0; its generator runs on."""
        col = self._slots.column(drone_id)
        floats = self._slots.arrays["floats"]
        floats[:, col] = 0.0
        floats[_ATT, col] = (1.0, 0.0, 0.0, 0.0)
        self._slots.record(drone_id).start_step = self._ticks

    def set_velocity_command(self, drone_id: int, velocity_m_s: FloatsLike) -> None:
        """One drone's latest /uav/input/velocity (m/s, world). ValueError on non-finite input."""
        col = self._slots.column(drone_id)
        self._slots.arrays["floats"][_CMD, col] = as_finite_floats("velocity_m_s", velocity_m_s, 3)

    def time_s(self, drone_id: int) -> float:
        """One drone's simulated time since it joined or was reset (s)."""
        return (self._ticks - self._slots.record(drone_id).start_step) * self.dt_s

    def state(self, drone_id: int) -> SimpleSimState:
        """One drone's true kinematic state (no noise)."""
        s = self._slots.arrays["floats"][:, self._slots.column(drone_id)].tolist()
        return SimpleSimState(self.time_s(drone_id), (*s[0:3],), (*s[3:6],), (*s[13:17],), s[_WOBBLE])

    def gps(self, drone_id: int) -> GpsReading:
        """One drone's latest GPS reading; before its first tick, the noise-free origin."""
        s = self._slots.arrays["floats"][:, self._slots.column(drone_id)].tolist()
        return GpsReading(self.time_s(drone_id), (*s[10:13],), (*s[13:17],))

    def advance(self, duration_s: float) -> int:
        """Tick every drone for duration_s, carrying the remainder; returns the ticks taken."""
        return self._clock.run(duration_s, self.tick)

    def tick(self) -> None:
        """One 1/rate_hz step of the lab's timer callback, for every drone."""
        self._ticks += 1
        floats = self._slots.arrays["floats"]
        if not floats.shape[1]:
            return
        p, dt = self.params, self.dt_s
        cap = p.max_velocity_step_m_s
        change = floats[_CMD] - floats[_VEL]
        change *= cap / np.maximum(np.abs(change), cap)  # exactly 1 unless an axis exceeds the cap
        wobble = floats[_WOBBLE]
        sigma = (
            np.abs(wobble) / 10.0
            if p.wobble_noise == "lab"
            else np.full_like(wobble, p.wobble_tilt_rad / 10.0)
        )
        wobble_noise, gps_noise = self._draw(sigma.tolist(), p.gps_noise_m)
        wobble += dt * (p.wobble_speed + wobble_noise)
        tilt = p.wobble_tilt_rad
        floats[_ATT] = np.array(
            [euler_sxyz_to_quat(tilt * math.cos(w), tilt * math.sin(w), 0.0) for w in wobble.tolist()]
        ).T
        floats[_VEL] += change
        floats[_POS] += floats[_VEL] * dt
        floats[_GPS] = floats[_POS] + gps_noise

    def _draw(self, wobble_sigmas: list[float], gps_sigma: float) -> tuple[np.ndarray, np.ndarray]:
        """Each drone's wobble and GPS noise for this tick, drawn from its own generator in the lab's
        order (wobble, then x, y, z) and, as the lab does, not drawn at all where sigma is 0."""
        wobble, gps = [], []
        for record, sigma in zip(self._slots.records, wobble_sigmas, strict=True):
            rng = record.rng
            draws = (
                []
                if rng is None
                else rng.standard_normal(int(sigma != 0.0) + 3 * int(gps_sigma != 0.0)).tolist()
            )
            wobble.append(sigma * draws.pop(0) if draws and sigma != 0.0 else 0.0)
            gps.append([gps_sigma * d for d in draws] if draws else [0.0, 0.0, 0.0])
        return np.array(wobble), np.array(gps).T


class SimpleDrone(DroneHandle["SimpleSimBatch"]):
    """One drone of a SimpleSimBatch: set its velocity command and read its GPS between ticks."""

    __slots__ = ()

    @property
    def state(self) -> SimpleSimState:
        return self._batch.state(self.id)

    @property
    def gps(self) -> GpsReading:
        return self._batch.gps(self.id)

    def set_velocity_command(self, velocity_m_s: FloatsLike) -> None:
        self._batch.set_velocity_command(self.id, velocity_m_s)

    def reset(self) -> None:
        self._batch.reset(self.id)
