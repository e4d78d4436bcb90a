"""The retuned cascade on the rotor physics: hover, steps, velocity mode, abuse. Controllers at 50 Hz."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sim.control import ClosedLoop
from sim.quadrotor import MotorSpeedCommand, QuadrotorParams, QuadrotorSim, QuadrotorState, RateThrustCommand

HOVER_ROTOR_RAD_S = math.sqrt(1.0 * 9.81 / (4 * 1.91e-6))  # sqrt(m g / (4 k_T)), about 1133


def _positions(states: list[QuadrotorState]) -> np.ndarray:
    return np.array([s.position_m for s in states])


@pytest.fixture(scope="module")
def takeoff_and_hover() -> list[QuadrotorState]:
    """From the ground at the origin to the default setpoint (0, 0, 3), 12 s."""
    loop = ClosedLoop(QuadrotorSim(noise=False))
    return loop.run(12.0)


@pytest.fixture(scope="module")
def step_to_5_5_10() -> list[QuadrotorState]:
    """Hovering at (0, 0, 3), then a step setpoint to (5, 5, 10), 15 s."""
    sim = QuadrotorSim(noise=False, initial_position_m=(0.0, 0.0, 3.0), rotors_at_hover=True)
    loop = ClosedLoop(sim)
    loop.run(2.0)
    loop.set_position_setpoint((5.0, 5.0, 10.0))
    return loop.run(15.0)


def test_hover_default_setpoint_holds_altitude_within_2cm(takeoff_and_hover: list[QuadrotorState]) -> None:
    settled = _positions([s for s in takeoff_and_hover if s.time_s >= 6.0])
    assert np.all(np.abs(settled[:, 2] - 3.0) < 0.02)
    assert np.all(np.abs(settled[:, :2]) < 0.03)


def test_hover_rotor_speeds_match_weight_balance(takeoff_and_hover: list[QuadrotorState]) -> None:
    rotors = takeoff_and_hover[-1].rotor_speeds_rad_s
    assert pytest.approx(1133.15, abs=0.01) == HOVER_ROTOR_RAD_S
    assert np.all(np.abs(rotors / HOVER_ROTOR_RAD_S - 1.0) < 0.01)


def test_hover_takeoff_climbs_without_touching_down_again(takeoff_and_hover: list[QuadrotorState]) -> None:
    z = _positions(takeoff_and_hover)[:, 2]
    assert z[5] > 0.0 and np.all(z[5:] > 0.0)
    assert z.max() < 3.5


def test_step_5_5_10_settles_within_10cm_by_10s(step_to_5_5_10: list[QuadrotorState]) -> None:
    target = np.array([5.0, 5.0, 10.0])
    step_start = step_to_5_5_10[0].time_s - 0.02
    error = np.abs(_positions(step_to_5_5_10) - target).max(axis=1)
    outside = np.nonzero(error >= 0.1)[0]
    settle_s = step_to_5_5_10[outside[-1] + 1].time_s - step_start
    assert settle_s <= 10.0
    assert error[-1] < 0.02


def test_step_5_5_10_overshoot_below_half_metre(step_to_5_5_10: list[QuadrotorState]) -> None:
    beyond = _positions(step_to_5_5_10) - np.array([5.0, 5.0, 10.0])  # every axis steps upwards
    assert np.all(beyond.max(axis=0) < 0.5)


def test_step_5_5_10_respects_tilt_and_speed_limits(step_to_5_5_10: list[QuadrotorState]) -> None:
    tilts = [
        math.acos(max(-1.0, min(1.0, math.cos(s.roll_rad) * math.cos(s.pitch_rad)))) for s in step_to_5_5_10
    ]
    assert max(tilts) < 0.5 * math.sqrt(2) + 0.05
    speeds_xy = [float(np.hypot(*s.velocity_m_s[:2])) for s in step_to_5_5_10]
    assert max(speeds_xy) < 4.0 * 1.05


def test_velocity_mode_tracks_world_velocity_setpoint() -> None:
    sim = QuadrotorSim(noise=False, initial_position_m=(0.0, 0.0, 5.0), rotors_at_hover=True)
    loop = ClosedLoop(sim)
    loop.set_velocity_setpoint((2.0, -1.0, 0.5))
    states = loop.run(6.0)
    assert states[-1].velocity_m_s == pytest.approx([2.0, -1.0, 0.5], abs=0.05)


def test_yaw_setpoint_turns_heading_and_still_holds_position() -> None:
    sim = QuadrotorSim(noise=False, initial_position_m=(1.0, 2.0, 3.0), rotors_at_hover=True)
    loop = ClosedLoop(sim)
    loop.set_position_setpoint((1.0, 2.0, 3.0), yaw_rad=2.5)
    states = loop.run(8.0)
    assert states[-1].yaw_rad == pytest.approx(2.5, abs=0.02)
    assert states[-1].position_m == pytest.approx([1.0, 2.0, 3.0], abs=0.05)


def test_hover_with_process_noise_stays_near_setpoint() -> None:
    sim = QuadrotorSim(
        rng=np.random.default_rng(11), initial_position_m=(0.0, 0.0, 3.0), rotors_at_hover=True
    )
    positions = _positions(ClosedLoop(sim).run(8.0))
    assert np.all(np.abs(positions - [0.0, 0.0, 3.0]) < 0.1)


def _assert_physical(state: QuadrotorState) -> None:
    values = np.concatenate(
        [
            state.position_m,
            state.velocity_m_s,
            state.attitude_wxyz,
            state.body_rates_rad_s,
            state.rotor_speeds_rad_s,
        ]
    )
    assert np.all(np.isfinite(values))
    assert state.position_m[2] >= 0.0
    # Full thrust plus gravity against quadratic drag bounds the speed: c v^2 <= T_max + m g.
    assert np.linalg.norm(state.velocity_m_s) <= math.sqrt((4 * 1.91e-6 * 2200**2 + 9.81) / 0.1)
    assert np.all((state.rotor_speeds_rad_s >= 0.0) & (state.rotor_speeds_rad_s <= 2200.0))
    assert abs(np.linalg.norm(state.attitude_wxyz) - 1.0) < 1e-9


def test_wild_setpoints_every_tick_for_60s_stay_physical() -> None:
    rng = np.random.default_rng(2024)
    sim = QuadrotorSim(rng=np.random.default_rng(5))
    loop = ClosedLoop(sim)
    for tick in range(3000):
        if tick % 2:
            loop.set_position_setpoint(rng.uniform(-100.0, 100.0, 3), yaw_rad=rng.uniform(-10, 10))
        else:
            loop.set_velocity_setpoint(rng.uniform(-50.0, 50.0, 3), yaw_rad=rng.uniform(-10, 10))
        _assert_physical(loop.tick())
    _assert_physical(sim.state)


def test_wild_raw_rate_thrust_commands_stay_physical() -> None:
    rng = np.random.default_rng(99)
    sim = QuadrotorSim(
        rng=np.random.default_rng(6), initial_position_m=(0.0, 0.0, 20.0), rotors_at_hover=True
    )
    max_rate = 0.0
    for _ in range(1000):
        rates = tuple(rng.uniform(-1e6, 1e6, 3))
        sim.set_command(RateThrustCommand(rates, float(rng.uniform(-1e6, 1e6))))
        sim.advance(0.02)
        state = sim.state
        _assert_physical(state)
        max_rate = max(max_rate, float(np.abs(state.body_rates_rad_s).max()))
    assert max_rate < 30.0  # commands clamp to 10 rad/s; the loop overshoots a little


def test_closed_loop_non_finite_setpoint_raises_and_keeps_flying_to_old_one() -> None:
    sim = QuadrotorSim(noise=False, initial_position_m=(0.0, 0.0, 3.0), rotors_at_hover=True)
    loop = ClosedLoop(sim)
    with pytest.raises(ValueError, match="setpoint_m"):
        loop.set_position_setpoint((1.0, math.nan, 3.0))
    with pytest.raises(ValueError, match="velocity_m_s"):
        loop.set_velocity_setpoint((math.inf, 0.0, 0.0))
    assert loop.run(3.0)[-1].position_m == pytest.approx([0.0, 0.0, 3.0], abs=0.02)


def test_wild_motor_speed_commands_stay_physical_and_spin_is_capped() -> None:
    rng = np.random.default_rng(17)
    sim = QuadrotorSim(rng=np.random.default_rng(8), initial_position_m=(0.0, 0.0, 50.0))
    sim.set_command(MotorSpeedCommand((2200.0, 0.0, 2200.0, 0.0)))  # pure yaw torque, nothing resists it
    sim.advance(5.0)
    assert abs(sim.state.body_rates_rad_s[2]) == 60.0
    for _ in range(1000):
        sim.set_command(MotorSpeedCommand(tuple(rng.uniform(-1e5, 1e5, 4))))
        sim.advance(0.02)
        _assert_physical(sim.state)
        assert np.all(np.abs(sim.state.body_rates_rad_s) <= 60.0)


def test_cascade_heavier_drone_than_modelled_recovers_altitude_by_integral() -> None:
    """A 20 % mass mismatch sags the hover; the z integral (which only integrates near rest) brings it back."""
    sim = QuadrotorSim(
        QuadrotorParams(mass_kg=1.2), noise=False, initial_position_m=(0.0, 0.0, 3.0), rotors_at_hover=True
    )
    loop = ClosedLoop(sim)
    loop.velocity.mass_kg = 1.0  # the controller's hover feed-forward believes the nominal 1 kg
    loop.set_position_setpoint((0.0, 0.0, 3.0))
    sagged = min(s.position_m[2] for s in loop.run(10.0))
    assert sagged < 2.8, "the mismatch is real"
    z = [s.position_m[2] for s in loop.run(50.0)]
    assert abs(z[-1] - 3.0) < 0.02
