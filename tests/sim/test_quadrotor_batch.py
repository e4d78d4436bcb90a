"""QuadrotorBatch: exact per-drone replay, physics across a batch, isolation, drones joining and leaving.

Everything steps simulated time; nothing sleeps. "Exactly" means bit for bit: np.array_equal.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import pytest

from sim.control import Cascade
from sim.quadrotor import (
    Command,
    Drone,
    DroneRemovedError,
    MotorSpeedCommand,
    QuadrotorBatch,
    QuadrotorParams,
    QuadrotorSim,
    QuadrotorState,
    RateThrustCommand,
)

G = 9.81
DRAG = 0.1
TICK_S = 0.02  # commands change at 50 Hz, like the lab's controllers
Pilot = Callable[[QuadrotorState], Command]
ARRAYS = ("position_m", "velocity_m_s", "attitude_wxyz", "body_rates_rad_s", "rotor_speeds_rad_s")


def _same_pose(a: QuadrotorState, b: QuadrotorState) -> bool:
    return all(np.array_equal(getattr(a, f), getattr(b, f)) for f in ARRAYS) and a.on_ground == b.on_ground


def _same(a: QuadrotorState, b: QuadrotorState) -> bool:
    return _same_pose(a, b) and a.time_s == b.time_s


def _mission(params: QuadrotorParams) -> Pilot:
    """Take off to (0, 0, 2), fly to (3, -2, 5) at 2 s, at 4 s cut thrust to 6 N and come down."""
    cascade = Cascade(params)
    cascade.set_position_setpoint((0.0, 0.0, 2.0))
    ticks = [0]

    def pilot(state: QuadrotorState) -> Command:
        ticks[0] += 1
        if ticks[0] == 100:
            cascade.set_position_setpoint((3.0, -2.0, 5.0), yaw_rad=0.7)
        command = cascade.command(state)
        return RateThrustCommand(command.body_rates_rad_s, 6.0) if ticks[0] > 200 else command

    return pilot


def _hold(command: Command) -> Pilot:
    return lambda _state: command


def _wild(seed: int) -> Pilot:
    rng = np.random.default_rng(seed)
    return lambda _state: RateThrustCommand(tuple(rng.uniform(-1e6, 1e6, 3)), float(rng.uniform(-1e6, 1e6)))


def _others(batch: QuadrotorBatch, count: int) -> list[tuple[Drone, Pilot]]:
    """Neighbours that fly anything but the mission: other setpoints, saturated motors, wild rate
    and thrust commands, or rest on the ground without noise."""
    flock: list[tuple[Drone, Pilot]] = []
    for i in range(count):
        drone = batch.add(rng=np.random.default_rng(1000 + i), noise=i % 4 != 3, position_m=(i, -i, i % 3))
        cascade = Cascade(batch.params)
        cascade.set_position_setpoint((-i, i, 1.0 + i / 3.0), yaw_rad=-1.0)
        pilots = [
            cascade.command,
            _hold(MotorSpeedCommand((2200.0, 0.0, 2200.0, 0.0))),
            _wild(i),
            _hold(RateThrustCommand((0.0, 0.0, 0.0), 0.0)),
        ]
        flock.append((drone, pilots[i % 4]))
    return flock


def _fly(
    batch: QuadrotorBatch, pilots: list[tuple[Drone, Pilot]], ticks: int, watch: Drone
) -> list[QuadrotorState]:
    """Every drone's pilot sets its command from its own state each tick; returns watch's state after each."""
    states = []
    for _ in range(ticks):
        for drone, pilot in pilots:
            drone.set_command(pilot(drone.state))
        batch.advance(TICK_S)
        states.append(watch.state)
    return states


def test_batch_drone_alone_or_among_30_replays_bit_for_bit() -> None:
    alone = QuadrotorSim(rng=np.random.default_rng(7))
    pilot = _mission(alone.params)
    solo = []
    for _ in range(300):  # 6 s: take-off from the ground, a step, a descent, with process noise
        alone.set_command(pilot(alone.state))
        alone.advance(TICK_S)
        solo.append(alone.state)

    batch = QuadrotorBatch()
    flock = _others(batch, 14)
    me = batch.add(rng=np.random.default_rng(7))
    flock += [(me, _mission(batch.params)), *_others(batch, 15)]
    crowd = _fly(batch, flock, 300, me)

    assert len(batch) == 30
    assert all(_same(a, b) for a, b in zip(solo, crowd, strict=True))
    # The mission really did go through the interesting regimes.
    heights = [s.position_m[2] for s in solo]
    assert solo[0].on_ground and not solo[100].on_ground
    assert max(heights) > 4.5 and heights[-1] < heights[200] - 1.0


def test_batch_hover_holds_altitude_for_every_drone_with_noise() -> None:
    batch = QuadrotorBatch()
    flock = []
    for i in range(30):
        x, y, z = 2.0 * (i % 6), 2.0 * (i // 6), 2.0 + 0.25 * i
        drone = batch.add(
            rng=np.random.default_rng(i), position_m=(x, y, z), yaw_rad=0.2 * i, rotors_at_hover=True
        )
        cascade = Cascade(batch.params)
        cascade.set_position_setpoint((x, y, z), yaw_rad=0.2 * i)
        flock.append((drone, cascade.command, (x, y, z)))
    worst = np.zeros(3)
    for _ in range(250):  # 5 s
        for drone, pilot, _ in flock:
            drone.set_command(pilot(drone.state))
        batch.advance(TICK_S)
        errors = [np.abs(d.state.position_m - np.array(sp)) for d, _, sp in flock]
        worst = np.maximum(worst, np.max(errors, axis=0))
    assert worst[2] < 0.02 and max(worst[0], worst[1]) < 0.03
    hover = math.sqrt(G / (4 * 1.91e-6))
    for drone, _, _ in flock:
        assert drone.state.rotor_speeds_rad_s == pytest.approx([hover] * 4, rel=0.01)


def test_batch_free_fall_matches_quadratic_drag_solution_for_every_drone() -> None:
    batch = QuadrotorBatch()
    heights = [10.0 + 5.0 * i for i in range(10)]
    fallers = [batch.add(noise=False, position_m=(i, 0.0, z)) for i, z in enumerate(heights)]
    for drone in fallers:
        drone.set_command(MotorSpeedCommand((0.0, 0.0, 0.0, 0.0)))
    flyer = batch.add(rng=np.random.default_rng(3), rotors_at_hover=True, position_m=(0, 0, 5))
    flyer.set_command(RateThrustCommand((3.0, -2.0, 1.0), 20.0))  # a neighbour that tumbles upwards
    terminal = math.sqrt(G / DRAG)
    for _ in range(1500):
        batch.step()
        t = fallers[0].time_s
        expected = [z0 - terminal**2 / G * math.log(math.cosh(G * t / terminal)) for z0 in heights]
        for drone, z in zip(fallers, expected, strict=True):
            if z > 0.0:
                assert drone.state.position_m[2] == pytest.approx(z, abs=1e-6)


def test_batch_quaternions_stay_unit_through_tumbling_for_every_drone() -> None:
    rng = np.random.default_rng(5)
    batch = QuadrotorBatch()
    drones = [
        batch.add(rng=np.random.default_rng(i), position_m=(i, 0.0, 300.0), rotors_at_hover=True)
        for i in range(30)
    ]
    worst = 0.0
    for _ in range(100):  # 5 s, a new random command for every drone every 50 ms
        for drone in drones:
            drone.set_command(
                RateThrustCommand(tuple(rng.uniform(-10.0, 10.0, 3)), float(rng.uniform(5.0, 15.0)))
            )
        for _ in range(50):
            batch.step()
        worst = max(worst, max(abs(float(np.linalg.norm(d.state.attitude_wxyz)) - 1.0) for d in drones))
    assert worst < 1e-9


@pytest.mark.parametrize(
    "wild",
    [
        MotorSpeedCommand((1e9, 0.0, 1e9, -1e9)),
        RateThrustCommand((1e9, -1e9, 1e9), 1e9),
        RateThrustCommand((0.0, 0.0, 0.0), -1e9),
    ],
    ids=["motors", "rates", "negative_thrust"],
)
def test_batch_one_drones_saturating_command_never_changes_another(wild: Command) -> None:
    def run(rogue_command: Command | None) -> tuple[list[QuadrotorState], QuadrotorState]:
        batch = QuadrotorBatch()
        drones = [batch.add(rng=np.random.default_rng(i), position_m=(i, 0.0, 3.0)) for i in range(6)]
        pilots = []
        for i, drone in enumerate(drones):
            cascade = Cascade(batch.params)
            cascade.set_position_setpoint((i, 1.0, 2.0 + i))
            pilots.append((drone, cascade.command))
        rogue = drones[2]
        if rogue_command is not None:
            pilots[2] = (rogue, lambda _s: rogue_command)
        for _ in range(150):
            for drone, pilot in pilots:
                drone.set_command(pilot(drone.state))
            batch.advance(TICK_S)
        return [d.state for d in drones if d is not rogue], rogue.state

    calm, calm_rogue = run(None)
    rough, rogue = run(wild)
    assert all(_same(a, b) for a, b in zip(calm, rough, strict=True))
    assert not _same(calm_rogue, rogue)
    assert np.all(np.isfinite(rogue.position_m)) and rogue.position_m[2] >= 0.0
    assert np.all((rogue.rotor_speeds_rad_s >= 0.0) & (rogue.rotor_speeds_rad_s <= 2200.0))


def _hovering_batch(seeds: list[int]) -> tuple[QuadrotorBatch, list[Drone]]:
    batch = QuadrotorBatch()
    drones = [
        batch.add(rng=np.random.default_rng(s), position_m=(s, 0, 2), rotors_at_hover=True) for s in seeds
    ]
    for i, drone in enumerate(drones):
        drone.set_command(RateThrustCommand((0.1 * i, -0.05, 0.2), 9.9))
    return batch, drones


def test_batch_drone_leaving_and_joining_leaves_the_others_untouched() -> None:
    steady, kept = _hovering_batch([1, 2, 3, 4])
    churn, churned = _hovering_batch([1, 2, 3, 4])
    steady.advance(0.777)
    churn.advance(0.777)
    churned[1].remove()
    newcomer = churn.add(rng=np.random.default_rng(99), position_m=(5, 5, 0))
    newcomer.set_command(RateThrustCommand((0.0, 0.0, 0.0), 15.0))
    steady.advance(1.5)
    churn.advance(1.5)
    churned[3].remove()
    steady.advance(1.0)
    churn.advance(1.0)
    assert _same(kept[0].state, churned[0].state) and _same(kept[2].state, churned[2].state)
    assert len(churn) == 3 and newcomer.state.position_m[2] > 0.5
    with pytest.raises(DroneRemovedError):
        _ = churned[1].state
    with pytest.raises(DroneRemovedError):
        churned[3].set_command(RateThrustCommand((0.0, 0.0, 0.0), 9.81))
    assert newcomer.id not in (d.id for d in churned)  # ids are never reused


def test_batch_late_joiner_replays_exactly_as_if_alone() -> None:
    batch, _ = _hovering_batch([11, 12, 13])
    batch.advance(1.2345)  # the batch's noise cursor is mid-block when the newcomer joins
    late = batch.add(rng=np.random.default_rng(42), position_m=(1, 2, 3), rotors_at_hover=True)
    alone = QuadrotorSim(rng=np.random.default_rng(42), initial_position_m=(1, 2, 3), rotors_at_hover=True)
    assert late.time_s == 0.0
    for k in range(120):  # 2.4 s, past the first 1024-step block of noise
        command = RateThrustCommand((math.sin(k / 10), 0.3, -0.2), 9.5 + math.cos(k / 7))
        late.set_command(command)
        alone.set_command(command)
        batch.advance(TICK_S)
        alone.advance(TICK_S)
        assert _same(late.state, alone.state)


def test_batch_reset_one_drone_replays_as_a_reset_sim_and_leaves_the_others() -> None:
    steady, kept = _hovering_batch([1, 2, 3])
    reset, drones = _hovering_batch([1, 2, 3])
    alone = QuadrotorSim(rng=np.random.default_rng(2), initial_position_m=(2, 0, 2), rotors_at_hover=True)
    alone.set_command(RateThrustCommand((0.1, -0.05, 0.2), 9.9))
    for batch in (steady, reset):
        batch.advance(0.5)
    alone.advance(0.5)
    drones[1].reset((0.0, 1.0, 4.0), yaw_rad=1.0, rotors_at_hover=True)
    alone.reset((0.0, 1.0, 4.0), yaw_rad=1.0, rotors_at_hover=True)
    assert drones[1].time_s == 0.0 and drones[1].state.position_m.tolist() == [0.0, 1.0, 4.0]
    for batch in (steady, reset):
        batch.advance(1.3)
    alone.advance(1.3)
    assert _same(kept[0].state, drones[0].state) and _same(kept[2].state, drones[2].state)
    assert _same(drones[1].state, alone.state)


def test_batch_one_generator_for_two_drones_is_refused() -> None:
    batch = QuadrotorBatch()
    rng = np.random.default_rng(1)
    batch.add(rng=rng)
    with pytest.raises(ValueError, match="its own"):
        batch.add(rng=rng)
    assert len(batch) == 1


def test_batch_bad_join_changes_nothing() -> None:
    batch = QuadrotorBatch()
    with pytest.raises(ValueError, match="rng"):
        batch.add(noise=True)
    with pytest.raises(ValueError, match="finite"):
        batch.add(noise=False, position_m=(0.0, math.nan, 1.0))
    assert len(batch) == 0
    batch.advance(0.01)  # an empty batch steps: its clock moves, nothing else
    assert batch.add(noise=False).time_s == 0.0


def test_batch_non_finite_step_freezes_only_that_drone() -> None:
    batch, drones = _hovering_batch([1, 2, 3])
    steady, kept = _hovering_batch([1, 2, 3])
    batch.advance(0.1)
    steady.advance(0.1)
    # No command can do this (inputs are clamped); plant a finite but absurd rotor speed whose
    # square overflows, to check the guard: that drone keeps its last state, the others fly on.
    batch._slots.arrays["floats"][13, 1] = 1e200
    frozen = drones[1].state
    with np.errstate(over="ignore", invalid="ignore"):
        batch.advance(0.5)
    steady.advance(0.5)
    assert drones[1].fault is not None and "non-finite" in drones[1].fault
    assert _same_pose(drones[1].state, frozen)
    assert _same(drones[0].state, kept[0].state) and _same(drones[2].state, kept[2].state)
    drones[1].reset((0.0, 0.0, 1.0))
    batch.advance(0.1)
    assert drones[1].fault is None and np.all(np.isfinite(drones[1].state.position_m))
