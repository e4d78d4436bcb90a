"""kinematics(): the floats a dynamics node publishes, equal to the state snapshot's values."""

from __future__ import annotations

import numpy as np

from sim.quadrotor import QuadrotorBatch, QuadrotorSim, QuadrotorState, RateThrustCommand
from sim.quadrotor.state import Kinematics


def _from_state(s: QuadrotorState) -> list[float]:
    return [
        *s.position_m.tolist(),
        *s.velocity_m_s.tolist(),
        *s.attitude_wxyz.tolist(),
        *s.body_rates_rad_s.tolist(),
    ]


def _check(k: Kinematics, s: QuadrotorState) -> None:
    assert all(type(v) is float for v in k)  # plain floats: messages take them unchecked
    assert list(k) == _from_state(s)  # the very same values, bit for bit


def test_a_flying_drone_reports_the_same_floats_as_its_state_alone_and_in_a_batch() -> None:
    alone = QuadrotorSim(rng=np.random.default_rng(7), noise=True)
    batch = QuadrotorBatch()
    others = [batch.add(rng=np.random.default_rng(seed), noise=True) for seed in (1, 2)]
    drone = batch.add(rng=np.random.default_rng(7), noise=True)
    command = RateThrustCommand((0.4, -0.3, 0.2), 13.0)  # climbing while it rolls, pitches and yaws
    alone.set_command(command)
    drone.set_command(command)
    others[0].set_command(RateThrustCommand((-0.2, 0.1, 0.0), 11.0))
    for _ in range(5):
        alone.advance(0.2)
        batch.advance(0.2)
        _check(alone.kinematics(), alone.state)
        _check(drone.kinematics(), drone.state)
        _check(others[0].kinematics(), others[0].state)
    position = alone.kinematics()[0:3]
    assert position[2] > 0.1 and np.hypot(position[0], position[1]) > 0.0  # it flew, and moved sideways
    assert drone.kinematics() == alone.kinematics()  # the batch replays the drone as it flies alone
