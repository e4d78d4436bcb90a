"""A batch of N drones against N separate single sims with the same seeds and commands: the same
trajectories, every float equal (==) at every control tick, and a drone the same alone, in a
batch of one, or in a batch of 30.

QuadrotorSim steps in plain floats and QuadrotorBatch in numpy columns; they evaluate the same
expressions in the same order with IEEE 754's correctly rounded operations, so equality is
exact, not a tolerance. Each drone draws its process noise from its own seeded generator. Time
is stepped, never slept.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable

import numpy as np
import pytest

from sim.control import LAB_PID_DT_S, Cascade, LabPositionController
from sim.quadrotor import (
    Command,
    MotorSpeedCommand,
    QuadrotorBatch,
    QuadrotorParams,
    QuadrotorSim,
    QuadrotorState,
    RateThrustCommand,
    SimpleSim,
    SimpleSimBatch,
    SimpleSimParams,
)
from sim.quadrotor.step_kernel import FEW_IN_CONTACT

TICK_S = 0.02  # commands change at 50 Hz, like the lab's controllers
ARRAYS = ("position_m", "velocity_m_s", "attitude_wxyz", "body_rates_rad_s", "rotor_speeds_rad_s")
Pilot = Callable[[QuadrotorState], Command]


def _equal(a: QuadrotorState, b: QuadrotorState) -> bool:
    return (
        all(np.array_equal(getattr(a, f), getattr(b, f)) for f in ARRAYS)
        and a.on_ground == b.on_ground
        and a.time_s == b.time_s
    )


@dataclasses.dataclass(frozen=True)
class Flight:
    """One drone's start and its pilot, made afresh for each run from the drone's index."""

    index: int
    params: QuadrotorParams
    seed_offset: int = 0

    @property
    def seed(self) -> int:
        return 100 + self.index + self.seed_offset

    @property
    def noise(self) -> bool:
        return self.index % 5 != 4

    @property
    def start(self) -> tuple[tuple[float, float, float], float]:
        """Position and yaw: some start in the air, some on the ground facing past pi (yaw 3.5 is
        -2.78 rad as 'sxyz' yaw, so the settling heading lies in the quaternion's other hemisphere)."""
        i = self.index
        return (float(i % 6), float(i // 6), 4.0 if i % 7 == 3 else 0.0), (3.5 if i % 3 == 0 else 0.4 * i)

    def pilot(self) -> Pilot:
        i, kind = self.index, self.index % 6
        cascade = Cascade(self.params)
        cascade.set_position_setpoint((i % 6 + 2.0, 1.0, 1.0 + 0.1 * i), yaw_rad=0.3 * i - 2.0)
        rng = np.random.default_rng(10_000 + i)
        ticks = [0]

        def fly(state: QuadrotorState) -> Command:
            ticks[0] += 1
            t = ticks[0]
            if kind == 0:  # take off, fly sideways low, cut thrust: a tilted, sliding touchdown
                command = cascade.command(state)
                return RateThrustCommand((0.4, -0.3, 0.2), 2.0) if t > 90 else command
            if kind == 1:  # saturated differential motors (a tumble), then motors off: a fall
                return MotorSpeedCommand((2200.0, 900.0, 2200.0, 0.0) if t < 20 else (0.0, 0.0, 0.0, 0.0))
            if kind == 2:  # wild commands, clamped by the sim
                rates = rng.uniform(-50.0, 50.0, 3)
                return RateThrustCommand((rates[0], rates[1], rates[2]), float(rng.uniform(-5.0, 40.0)))
            if kind == 3:  # thrust below the weight and a yaw rate: rests, turns, settles level
                return RateThrustCommand((0.5, -0.5, 1.5), 6.0 + 0.1 * i)
            if kind == 4:  # the cascade throughout: take-off and hover
                return cascade.command(state)
            # Staggered lift-off: some rest while others lift off, with a push sideways on the ground.
            return RateThrustCommand((0.0, 0.3, 0.0), 5.0 if t < 10 + 4 * (i % 4) else 12.0)

        return fly


def _flights(n: int, params: QuadrotorParams) -> list[Flight]:
    return [Flight(i, params) for i in range(n)]


def _scalar(flight: Flight, ticks: int, physics_rate_hz: float) -> list[QuadrotorState]:
    (position, yaw), p = flight.start, flight.params
    sim = QuadrotorSim(
        p,
        rng=np.random.default_rng(flight.seed),
        noise=flight.noise,
        physics_rate_hz=physics_rate_hz,
        initial_position_m=position,
        initial_yaw_rad=yaw,
    )
    pilot, states = flight.pilot(), []
    for _ in range(ticks):
        sim.set_command(pilot(sim.state))
        sim.advance(TICK_S)
        states.append(sim.state)
    return states


def _batched(flights: list[Flight], ticks: int, physics_rate_hz: float) -> list[list[QuadrotorState]]:
    batch = QuadrotorBatch(flights[0].params, physics_rate_hz=physics_rate_hz)
    drones = []
    for flight in flights:
        position, yaw = flight.start
        drone = batch.add(
            rng=np.random.default_rng(flight.seed), noise=flight.noise, position_m=position, yaw_rad=yaw
        )
        drones.append((drone, flight.pilot()))
    states: list[list[QuadrotorState]] = [[] for _ in flights]
    for _ in range(ticks):
        for drone, pilot in drones:
            drone.set_command(pilot(drone.state))
        batch.advance(TICK_S)
        for row, (drone, _) in zip(states, drones, strict=True):
            row.append(drone.state)
    return states


def _assert_same(alone: list[QuadrotorState], batched: list[QuadrotorState], label: str) -> None:
    for tick, (a, b) in enumerate(zip(alone, batched, strict=True)):
        assert _equal(a, b), f"{label}: first difference at control tick {tick} (t = {a.time_s:.3f} s)"


def test_batch_of_30_reproduces_30_separate_sims_exactly_through_every_regime() -> None:
    ticks, flights = 175, _flights(30, QuadrotorParams())  # 3.5 s
    alone = [_scalar(f, ticks, 1000.0) for f in flights]
    batched = _batched(flights, ticks, 1000.0)
    for flight, a, b in zip(flights, alone, batched, strict=True):
        _assert_same(a, b, f"drone {flight.index}")

    # The flights went through the regimes the step has code for, and stayed physical.
    everything = [s for run in alone for s in run]
    assert all(np.all(np.isfinite(s.position_m)) and s.position_m[2] >= 0.0 for s in everything)
    assert all(abs(float(np.linalg.norm(s.attitude_wxyz)) - 1.0) < 1e-9 for s in everything)
    assert all(np.all((s.rotor_speeds_rad_s >= 0.0) & (s.rotor_speeds_rad_s <= 2200.0)) for s in everything)
    assert max(s.position_m[2] for s in alone[4]) > 1.0  # the cascade took off
    assert alone[0][-1].on_ground and max(s.position_m[2] for s in alone[0]) > 0.5  # flew, then landed
    sliding = [s for run in alone for s in run if s.on_ground and np.hypot(*s.velocity_m_s[:2]) > 0.05]
    assert sliding  # drones touched down or were pushed with horizontal speed and slid
    assert alone[1][-1].on_ground and max(np.max(np.abs(s.body_rates_rad_s)) for s in alone[1]) > 5.0
    assert alone[3][-1].on_ground and abs(alone[3][-1].roll_rad) < 1e-3  # rested level, yaw 3.5 start
    in_contact = [sum(run[t].on_ground for run in alone) for t in range(ticks)]
    assert max(in_contact) > FEW_IN_CONTACT >= min(in_contact) >= 1  # both of the batch's ground paths


@pytest.mark.parametrize(
    ("changes", "physics_rate_hz"),
    [
        ({"rate_filter_enabled": False, "gyroscopic_enabled": False}, 1000.0),
        ({"drag_coeff_n_per_m_s2": 0.0, "mass_kg": 1.3, "ground_friction_coeff": 0.1}, 500.0),
    ],
    ids=["no_filter_no_gyro", "heavier_no_drag_500hz"],
)
def test_batch_reproduces_separate_sims_with_other_params_and_rates(
    changes: dict[str, object], physics_rate_hz: float
) -> None:
    ticks, flights = 100, _flights(12, dataclasses.replace(QuadrotorParams(), **changes))  # type: ignore[arg-type]
    batched = _batched(flights, ticks, physics_rate_hz)
    for flight, b in zip(flights, batched, strict=True):
        _assert_same(_scalar(flight, ticks, physics_rate_hz), b, f"drone {flight.index}")


def test_a_drone_replays_the_same_alone_in_a_batch_of_one_and_in_a_batch_of_30() -> None:
    ticks, params = 125, QuadrotorParams()
    flights = _flights(30, params)
    crowd = _batched(flights, ticks, 1000.0)
    for index in (0, 14, 29):  # first, middle and last column
        flight = flights[index]
        alone = _scalar(flight, ticks, 1000.0)
        (one,) = _batched([flight], ticks, 1000.0)
        _assert_same(alone, one, f"drone {index} in a batch of one")
        _assert_same(alone, crowd[index], f"drone {index} among 30")
    # Equality is not trivial: the same flight (the cascade's take-off) with another noise seed differs.
    reseeded = dataclasses.replace(flights[10], seed_offset=1000)
    assert flights[10].noise and not np.array_equal(
        _scalar(reseeded, 20, 1000.0)[-1].position_m, crowd[10][19].position_m
    )


def test_simple_batch_of_30_reproduces_30_separate_simple_sims_exactly() -> None:
    def params(i: int) -> SimpleSimParams:
        return SimpleSimParams(wobble_noise="fixed") if i % 4 == 1 else SimpleSimParams()

    def controller(i: int) -> LabPositionController:
        return LabPositionController(setpoint_m=(i % 5 - 2.0, 0.5 * i, 1.0 + i % 3))

    sims = [
        (SimpleSim(params(i), rng=np.random.default_rng(i), noise=i % 3 != 2), controller(i))
        for i in range(30)
    ]
    # One batch per parameter set, as a server would keep them; each drone still ticks exactly as alone.
    batches = {"lab": SimpleSimBatch(SimpleSimParams()), "fixed": SimpleSimBatch(params(1))}
    drones = [
        (batches[params(i).wobble_noise].add(rng=np.random.default_rng(i), noise=i % 3 != 2), controller(i))
        for i in range(30)
    ]
    for _ in range(600):  # 6 s: the PIDs at 100 Hz on their GPS, the sims at 20 Hz
        for (sim, pid_a), (drone, pid_b) in zip(sims, drones, strict=True):
            sim.set_velocity_command(pid_a.update(sim.gps.position_m, LAB_PID_DT_S))
            drone.set_velocity_command(pid_b.update(drone.gps.position_m, LAB_PID_DT_S))
            sim.advance(LAB_PID_DT_S)
        for batch in batches.values():
            batch.advance(LAB_PID_DT_S)
        for (sim, _), (drone, _) in zip(sims, drones, strict=True):
            assert drone.state == sim.state and drone.gps == sim.gps
    # They flew to their setpoints, each with its own noise (the noisy ones' GPS differ from the truth).
    for i, (sim, pid) in enumerate(sims):
        assert np.allclose(sim.state.position_m, pid.setpoint_m, atol=0.1)
        assert (sim.gps.position_m != sim.state.position_m) == (i % 3 != 2)
    assert math.isfinite(sims[0][0].state.wobble_phase_rad)
