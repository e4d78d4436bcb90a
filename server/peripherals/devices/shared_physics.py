"""Every world's drone in one batch: the physics of a class server.

Each world's dynamics node (flightgoggles_uav_dynamics) finds this device on its bus and adds
its drone here instead of building its own QuadrotorSim. A node's tick brings the whole batch up
to the tick's time, so each 1 ms physics step runs once, vectorized, for every drone, however
the worlds' timers interleave; a world ticking later in the same millisecond finds the work
done. Each drone keeps its own seeded generator, so its noise does not depend on the others.
SharedSimpleSim does the same for the worlds that fly the lab's kinematic simple_sim
(``simple:=true``), at its 20 Hz.
"""

from __future__ import annotations

from typing import Generic, Protocol, TypeVar

import numpy as np

from node_runtime.bus import Clock
from sim.quadrotor import QuadrotorBatch, SimpleDrone, SimpleSimBatch, SimpleSimParams
from sim.quadrotor.batch import Drone

# How much time one late advance may fly; the rest of a stall is skipped, so a world starved of
# CPU flies slower than real time instead of flying open-loop on its last command.
# The quadrotor: one period of the flight controllers (50 Hz). Flying 0.1 s on a stale command, a
# 2 m step overshot by 0.24 m instead of 1.5 cm when the world ran 50-150 ms late.
QUADROTOR_MAX_CATCH_UP_S = 0.02
# simple_sim: its own 20 Hz ticks are the lab's timer, so a late world runs the ticks it missed.
SIMPLE_SIM_MAX_CATCH_UP_S = 0.1

H = TypeVar("H")
H_co = TypeVar("H_co", covariant=True)


class _Batch(Protocol[H_co]):
    def __len__(self) -> int: ...
    def add(self, *, rng: np.random.Generator | None = ..., noise: bool = ...) -> H_co: ...
    def advance(self, duration_s: float) -> int: ...


class SharedBatch(Generic[H]):
    """One batch of drones on the class clock, shared by every world's node (H: a drone's handle)."""

    def __init__(self, clock: Clock, batch: _Batch[H], max_catch_up_s: float) -> None:
        self.clock = clock
        self.batch = batch
        self.max_catch_up_s = max_catch_up_s
        self._at_s = clock.now()

    def __len__(self) -> int:
        return len(self.batch)

    def add(self, seed: int, noise: bool) -> H:
        """A new drone at rest at the origin; the others are first brought up to now."""
        self.advance_to(self.clock.now())
        return self.batch.add(rng=np.random.default_rng(seed) if noise else None, noise=noise)

    def advance_to(self, now_s: float) -> None:
        """Step every drone up to ``now_s`` (nothing if it is already there), at most
        ``max_catch_up_s`` of it: the rest of a longer gap is skipped."""
        elapsed = now_s - self._at_s
        if elapsed <= 0.0:
            return
        self.batch.advance(min(elapsed, self.max_catch_up_s))
        self._at_s = now_s


class SharedQuadrotorPhysics(SharedBatch[Drone]):
    """Every fly world's drone in one QuadrotorBatch, stepped at ``physics_rate_hz``."""

    def __init__(self, clock: Clock, physics_rate_hz: float = 1000.0) -> None:
        super().__init__(clock, QuadrotorBatch(physics_rate_hz=physics_rate_hz), QUADROTOR_MAX_CATCH_UP_S)
        self.physics_rate_hz = float(physics_rate_hz)


class SharedSimpleSim(SharedBatch[SimpleDrone]):
    """Every simple_sim world's drone in one SimpleSimBatch, ticked at the lab's 20 Hz on the class clock.

    A world's node brings the batch up to now on its timer and before it sets a velocity command,
    then publishes its drone's newest reading, so a drone's flight depends on when its commands
    came, not on the other worlds' timers.
    """

    def __init__(self, clock: Clock, params: SimpleSimParams | None = None) -> None:
        batch = SimpleSimBatch(params)
        super().__init__(clock, batch, SIMPLE_SIM_MAX_CATCH_UP_S)
        self.params = batch.params
