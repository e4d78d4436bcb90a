"""Ground contact: resting, lift-off, landing, friction, settling level."""

from __future__ import annotations

import math

import numpy as np

from sim.control import ClosedLoop
from sim.quadrotor import MotorSpeedCommand, QuadrotorSim, RateThrustCommand

G = 9.81
FRICTION = 0.5


def test_ground_rest_zero_thrust_stays_at_zero() -> None:
    sim = QuadrotorSim(noise=False)
    sim.set_command(RateThrustCommand((0.0, 0.0, 0.0), 0.0))
    for _ in range(100):
        sim.advance(0.05)
        state = sim.state
        assert state.position_m[2] == 0.0 and state.on_ground
        assert not np.any(state.velocity_m_s)


def test_ground_rest_with_process_noise_never_sinks() -> None:
    sim = QuadrotorSim(rng=np.random.default_rng(3))
    for _ in range(100):
        sim.advance(0.02)
        assert sim.state.position_m[2] == 0.0


def test_ground_rest_thrust_below_weight_stays_down() -> None:
    sim = QuadrotorSim(noise=False)
    sim.set_command(RateThrustCommand((0.0, 0.0, 0.0), 0.9 * G))
    sim.advance(2.0)
    assert sim.state.position_m[2] == 0.0 and sim.state.on_ground


def test_ground_takeoff_thrust_above_weight_lifts_off() -> None:
    sim = QuadrotorSim(noise=False)
    sim.set_command(RateThrustCommand((0.0, 0.0, 0.0), 15.0))
    heights = []
    for _ in range(50):
        sim.advance(0.02)
        heights.append(sim.state.position_m[2])
    assert not sim.state.on_ground
    assert np.all(np.diff(heights) >= 0.0)
    # Net 5.19 m/s^2 up once the rotors (tau 20 ms) have spun up, minus drag: about 2.6 m after 1 s.
    assert 2.0 < heights[-1] < 0.5 * (15.0 - G) * 1.0**2


def test_ground_landing_low_thrust_stops_at_zero_never_below() -> None:
    sim = QuadrotorSim(noise=False, initial_position_m=(0.0, 0.0, 3.0), rotors_at_hover=True)
    sim.set_command(RateThrustCommand((0.0, 0.0, 0.0), 7.0))
    landed_at = None
    for _ in range(200):
        sim.advance(0.02)
        state = sim.state
        assert state.position_m[2] >= 0.0
        if state.on_ground and landed_at is None:
            landed_at = state.time_s
    assert landed_at is not None and landed_at < 3.0
    assert sim.state.position_m[2] == 0.0 and sim.state.velocity_m_s[2] == 0.0


def test_ground_sliding_landing_friction_stops_within_coulomb_distance() -> None:
    sim = QuadrotorSim(noise=False, initial_position_m=(0.0, 0.0, 2.0), rotors_at_hover=True)
    loop = ClosedLoop(sim)
    loop.set_velocity_setpoint((3.0, 0.0, 0.0))
    loop.run(3.0)
    sim.set_command(MotorSpeedCommand((0.0, 0.0, 0.0, 0.0)))  # cut the motors in forward flight
    touchdown = None
    while sim.time_s < 8.0:
        sim.advance(0.001)
        if sim.state.on_ground and touchdown is None:
            touchdown = sim.state
    assert touchdown is not None
    speed = float(np.hypot(*touchdown.velocity_m_s[:2]))
    slid = float(np.hypot(*(sim.state.position_m[:2] - touchdown.position_m[:2])))
    assert speed > 1.0
    # Coulomb friction with the full weight on the legs: v^2 / (2 mu g), plus one step of slack.
    assert slid <= speed**2 / (2 * FRICTION * G) + speed * 0.001
    assert slid >= 0.9 * speed**2 / (2 * FRICTION * G)
    assert not np.any(sim.state.velocity_m_s)


def test_ground_landed_tilted_settles_level_keeping_heading() -> None:
    sim = QuadrotorSim(noise=False, initial_position_m=(0.0, 0.0, 1.0), rotors_at_hover=True)
    sim.set_command(RateThrustCommand((0.5, 0.3, 0.4), 9.0))
    sim.advance(0.5)
    roll, pitch, yaw_before = sim.state.euler_sxyz_rad
    assert abs(roll) > 0.05 and abs(pitch) > 0.05
    sim.set_command(MotorSpeedCommand((0.0, 0.0, 0.0, 0.0)))
    sim.advance(2.0)
    roll, pitch, yaw = sim.state.euler_sxyz_rad
    assert sim.state.on_ground
    assert abs(roll) < 1e-3 and abs(pitch) < 1e-3
    assert math.isfinite(yaw) and abs(yaw) > 0.05  # heading kept, not reset
    assert abs(math.remainder(yaw - yaw_before, 2 * math.pi)) < 0.5
