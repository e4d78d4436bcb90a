"""SimpleSimBatch: the lab's kinematic sim for many drones, each replaying exactly as it would alone."""

from __future__ import annotations

import numpy as np
import pytest

from sim.control import LAB_PID_DT_S, LabPositionController, SimpleModeLoop
from sim.quadrotor import (
    DroneRemovedError,
    GpsReading,
    SimpleDrone,
    SimpleSim,
    SimpleSimBatch,
    SimpleSimState,
)

DT = 0.05  # the sim's 20 Hz tick


def _fly(
    batch: SimpleSimBatch,
    pilots: list[tuple[SimpleDrone, LabPositionController]],
    seconds: float,
    watch: SimpleDrone,
) -> list[tuple[SimpleSimState, GpsReading]]:
    """The lab's PID per drone at 100 Hz on its own GPS, the batch at 20 Hz; watch's state and GPS after each tick."""
    samples = []
    for _ in range(round(seconds / LAB_PID_DT_S)):
        for drone, pid in pilots:
            drone.set_velocity_command(pid.update(drone.gps.position_m, LAB_PID_DT_S))
        if batch.advance(LAB_PID_DT_S):
            samples.append((watch.state, watch.gps))
    return samples


def _neighbours(batch: SimpleSimBatch, count: int) -> list[tuple[SimpleDrone, LabPositionController]]:
    return [
        (
            batch.add(rng=np.random.default_rng(500 + i), noise=i % 3 != 0),
            LabPositionController(setpoint_m=(i, -i, 2 * i)),
        )
        for i in range(count)
    ]


def test_simple_batch_drone_alone_or_among_30_replays_bit_for_bit() -> None:
    loop = SimpleModeLoop(SimpleSim(rng=np.random.default_rng(9)))
    loop.set_setpoint((5.0, 5.0, 10.0))
    alone = loop.run(8.0)  # the lab's simple mode: its PID at 100 Hz on the GPS, the sim at 20 Hz

    batch = SimpleSimBatch()
    flock = _neighbours(batch, 20)
    me = batch.add(rng=np.random.default_rng(9))
    pid = LabPositionController()
    pid.set_setpoint((5.0, 5.0, 10.0))
    flock += [(me, pid), *_neighbours(batch, 9)]
    crowd = _fly(batch, flock, 8.0, me)

    assert len(batch) == 30
    assert [state for state, _ in crowd] == alone
    assert crowd[-1][1] == loop.sim.gps
    assert np.allclose(alone[-1].position_m, (5.0, 5.0, 10.0), atol=0.05)


def test_simple_batch_climb_matches_lab_recurrence_for_every_drone() -> None:
    batch = SimpleSimBatch()
    targets = [0.5 + 0.5 * i for i in range(9)]  # all below the 5 m/s per-tick cap
    pilots = [(batch.add(noise=False), LabPositionController(setpoint_m=(0.0, 0.0, z))) for z in targets]
    heights: list[list[float]] = [[] for _ in targets]
    for _ in range(500):  # 5 s
        for drone, pid in pilots:
            drone.set_velocity_command(pid.update(drone.gps.position_m, LAB_PID_DT_S))
        if batch.advance(LAB_PID_DT_S):
            for row, (drone, _) in zip(heights, pilots, strict=True):
                row.append(drone.state.position_m[2])
    # Kp = 1 on the previous tick's GPS: z_n = z_{n-1} + dt (z* - z_{n-1}) = z* (1 - 0.95^n).
    for row, z in zip(heights, targets, strict=True):
        assert row == pytest.approx([z * (1.0 - (1.0 - DT) ** n) for n in range(1, 101)], abs=1e-12)


def test_simple_batch_wild_command_never_changes_another() -> None:
    def run(wild: bool) -> tuple[list[SimpleSimState], SimpleSimState]:
        batch = SimpleSimBatch()
        drones = [batch.add(rng=np.random.default_rng(i)) for i in range(5)]
        for i, drone in enumerate(drones):
            drone.set_velocity_command((1e12, -1e12, 1e12) if wild and i == 2 else (i, 1.0, -i))
        batch.advance(3.0)
        return [d.state for i, d in enumerate(drones) if i != 2], drones[2].state

    calm, calm_rogue = run(False)
    rough, rogue = run(True)
    assert rough == calm
    assert rogue != calm_rogue and rogue.velocity_m_s == (300.0, -300.0, 300.0)  # 5 m/s per tick for 60 ticks


def test_simple_batch_leaving_joining_and_reset_leave_the_others_untouched() -> None:
    def start() -> tuple[SimpleSimBatch, list[SimpleDrone]]:
        batch = SimpleSimBatch()
        drones = [batch.add(rng=np.random.default_rng(i)) for i in range(4)]
        for i, drone in enumerate(drones):
            drone.set_velocity_command((0.1 * i, 0.2, -0.3))
        return batch, drones

    steady, kept = start()
    churn, churned = start()
    for batch in (steady, churn):
        batch.advance(1.05)
    churned[1].remove()
    churned[3].reset()
    late = churn.add(rng=np.random.default_rng(77))
    alone = SimpleSim(rng=np.random.default_rng(77))
    for batch in (steady, churn):
        batch.advance(2.0)
    readings = alone.advance(2.0)
    assert churned[0].state == kept[0].state and churned[2].gps == kept[2].gps
    assert late.gps == readings[-1] and late.state == alone.state
    assert churned[3].time_s == pytest.approx(2.0) and churned[3].state.position_m != kept[3].state.position_m
    with pytest.raises(DroneRemovedError):
        churned[1].set_velocity_command((0.0, 0.0, 0.0))


def test_simple_batch_shared_generator_or_bad_command_refused_and_changes_nothing() -> None:
    batch = SimpleSimBatch()
    rng = np.random.default_rng(1)
    drone = batch.add(rng=rng)
    with pytest.raises(ValueError, match="its own"):
        batch.add(rng=rng)
    drone.set_velocity_command((1.0, 0.0, 0.0))
    with pytest.raises(ValueError, match="velocity_m_s"):
        drone.set_velocity_command((float("nan"), 0.0, 0.0))
    batch.tick()
    assert len(batch) == 1 and drone.state.velocity_m_s == (1.0, 0.0, 0.0)
