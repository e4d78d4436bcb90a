"""The lab's kinematic simple_sim and its position PID reproduce lab reference §3.3-3.4."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sim.control import LabPositionController, SimpleModeLoop
from sim.quadrotor import SimpleSim, SimpleSimParams, quat_to_euler_sxyz
from sim.quadrotor.simple_sim import WobbleNoise

DT = 0.05  # the sim's 20 Hz tick


def _hover_loop() -> SimpleModeLoop:
    """Noise-free simple mode after 30 s at the default setpoint: at rest at (0, 0, 3) to ~1e-13."""
    loop = SimpleModeLoop(SimpleSim(noise=False))
    loop.run(30.0)
    return loop


def test_simple_sim_no_command_stays_at_origin() -> None:
    sim = SimpleSim(rng=np.random.default_rng(0), noise=False)
    sim.advance(3.0)
    assert sim.state.position_m == (0.0, 0.0, 0.0)


def test_simple_sim_velocity_change_capped_at_5_m_s_per_tick_per_axis() -> None:
    sim = SimpleSim(noise=False)
    sim.set_velocity_command((12.0, -3.0, -7.0))
    velocities = []
    for _ in range(3):
        sim.tick()
        velocities.append(sim.state.velocity_m_s)
    assert velocities == [(5.0, -3.0, -5.0), (10.0, -3.0, -7.0), (12.0, -3.0, -7.0)]
    # Explicit Euler with the new velocity: x = dt * (5 + 10 + 12).
    assert sim.state.position_m[0] == pytest.approx(DT * 27.0)


def test_simple_sim_no_gravity_no_ground_goes_below_zero() -> None:
    sim = SimpleSim(noise=False)
    sim.set_velocity_command((0.0, 0.0, -1.0))
    sim.advance(2.0)
    assert sim.state.position_m[2] == pytest.approx(-2.0)


def test_simple_mode_climb_matches_first_order_recurrence_and_lab_2_98m() -> None:
    loop = SimpleModeLoop(SimpleSim(noise=False), controller_start_s=5.0)
    states = loop.run(10.0)
    z = [s.position_m[2] for s in states]
    assert z[:100] == [0.0] * 100  # nothing moves before the controller's 5 s sleep ends
    # Kp = 1 on the previous tick's GPS: z_n = z_{n-1} + dt (3 - z_{n-1}) = 3 (1 - 0.95^n).
    expected = [3.0 * (1.0 - (1.0 - DT) ** n) for n in range(1, 101)]
    assert z[100:] == pytest.approx(expected, abs=1e-12)
    assert z[-1] == pytest.approx(2.98, abs=0.005)


def test_simple_mode_step_to_5_5_10_first_tick_capped_then_within_5cm_near_5s() -> None:
    loop = _hover_loop()
    loop.set_setpoint((5.0, 5.0, 10.0))
    states = loop.run(8.0)
    # Tick 1: the commands are (5, 5, 7); only z exceeds the 5 m/s cap.
    assert states[0].velocity_m_s == pytest.approx((5.0, 5.0, 5.0), abs=1e-9)
    # Independent recurrences: x_n = 5 - 5 (0.95)^n, z_n = 10 - 6.75 (0.95)^(n-1) after the capped tick.
    n = np.arange(1, len(states) + 1)
    x_expected = 5.0 - 5.0 * 0.95**n
    z_expected = 10.0 - 6.75 * 0.95 ** (n - 1)
    positions = np.array([s.position_m for s in states])
    assert positions[:, 0] == pytest.approx(x_expected, abs=1e-9)
    assert positions[:, 2] == pytest.approx(z_expected, abs=1e-9)
    inside = np.all(np.abs(positions - [5.0, 5.0, 10.0]) < 0.05, axis=1)
    first_inside_s = DT * (int(np.argmax(inside)) + 1)
    assert first_inside_s == pytest.approx(4.85, abs=1e-9)  # "within 0.05 m in about 5 s"
    assert np.all(inside[int(np.argmax(inside)) :])


def test_simple_sim_gps_noise_has_lab_sigma_and_attitude_is_noise_free() -> None:
    sim = SimpleSim(rng=np.random.default_rng(42))
    readings = sim.advance(200.0)
    errors = np.array([r.position_m for r in readings])  # true position stays at the origin
    assert np.std(errors, axis=0) == pytest.approx([0.01] * 3, rel=0.05)
    assert readings[-1].attitude_wxyz == sim.state.attitude_wxyz


def test_simple_sim_wobble_tilt_bounded_by_pi_over_16() -> None:
    sim = SimpleSim(rng=np.random.default_rng(1))
    for reading in sim.advance(30.0):
        roll, pitch, yaw = quat_to_euler_sxyz(reading.attitude_wxyz)
        assert math.hypot(roll, pitch) <= math.pi / 16 + 1e-9
        assert abs(yaw) < 1e-12


@pytest.mark.parametrize(("mode", "low", "high"), [("lab", 0.1, math.inf), ("fixed", 0.0, 0.01)])
def test_simple_sim_wobble_noise_lab_bug_grows_with_phase(mode: WobbleNoise, low: float, high: float) -> None:
    sim = SimpleSim(SimpleSimParams(wobble_noise=mode), rng=np.random.default_rng(5))
    phases = []
    for _ in range(2000):
        sim.tick()
        phases.append(sim.state.wobble_phase_rad)
    # Phase increments are dt (1 + N(0, sigma)); in the lab's version sigma = phase / 10.
    jitter = np.std(np.diff(phases[-500:]) - DT)
    assert low < jitter < high


def test_simple_sim_same_seed_replays() -> None:
    runs = [SimpleSim(rng=np.random.default_rng(9)).advance(2.0) for _ in range(2)]
    assert runs[0] == runs[1]


def test_simple_sim_non_finite_velocity_raises_and_keeps_command() -> None:
    sim = SimpleSim(noise=False)
    sim.set_velocity_command((1.0, 0.0, 0.0))
    with pytest.raises(ValueError, match="velocity_m_s"):
        sim.set_velocity_command((math.nan, 0.0, 0.0))
    sim.tick()
    assert sim.state.velocity_m_s == (1.0, 0.0, 0.0)


def test_lab_position_controller_default_setpoint_is_3m_hover() -> None:
    assert LabPositionController().update((0.0, 0.0, 0.0), 0.01) == (0.0, 0.0, 3.0)
