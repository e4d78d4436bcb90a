"""Open-loop physics of QuadrotorSim: integrator accuracy, free fall, mixer signs, commands."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from sim.quadrotor import MotorSpeedCommand, QuadrotorParams, QuadrotorSim, RateThrustCommand
from sim.quadrotor.dynamics import NO_NOISE, RigidBodyModel, normalize_quaternion, rk4_step
from sim.quadrotor.rate_control import RateLoop

G = 9.81
MASS_KG = 1.0
DRAG = 0.1


def _spin_state(rates: tuple[float, float, float]) -> list[float]:
    return [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, *rates, 0.0, 0.0, 0.0, 0.0]


def _torque_free_error(h: float, duration_s: float = 1.0) -> float:
    """Body-rate error of RK4 against the symmetric top's closed-form precession."""
    model = RigidBodyModel(QuadrotorParams())
    s = _spin_state((1.0, 0.0, 5.0))
    for _ in range(round(duration_s / h)):
        s = rk4_step(s, (0.0, 0.0, 0.0, 0.0), model, NO_NOISE, h)
    # Ixx = Iyy: w_z stays put and (w_x, w_y) turns at lam = (Izz - Ixx) / Ixx * w_z.
    lam = (0.0069 - 0.0049) / 0.0049 * 5.0
    expected = (math.cos(lam * duration_s), math.sin(lam * duration_s), 5.0)
    return max(abs(a - b) for a, b in zip(s[10:13], expected, strict=True))


def test_rk4_torque_free_spin_matches_closed_form_with_fourth_order_convergence() -> None:
    coarse, fine = _torque_free_error(0.004), _torque_free_error(0.002)
    assert _torque_free_error(0.001) < 1e-9
    # Halving the step divides the error by ~2^4 for a fourth-order method.
    assert 12.0 < coarse / fine < 20.0


def test_rk4_constant_yaw_rate_quaternion_matches_closed_form() -> None:
    model = RigidBodyModel(QuadrotorParams())
    s = _spin_state((0.0, 0.0, 2.0))
    for _ in range(1000):
        s = rk4_step(s, (0.0, 0.0, 0.0, 0.0), model, NO_NOISE, 0.001)
        normalize_quaternion(s)
    assert s[6:10] == pytest.approx([math.cos(1.0), 0.0, 0.0, math.sin(1.0)], abs=1e-12)


def _free_fall_from_10m() -> tuple[np.ndarray, np.ndarray, list]:
    sim = QuadrotorSim(noise=False, initial_position_m=(0.0, 0.0, 10.0))
    sim.set_command(MotorSpeedCommand((0.0, 0.0, 0.0, 0.0)))
    times, heights, states = [], [], []
    for _ in range(3000):
        sim.step()
        state = sim.state
        times.append(state.time_s)
        heights.append(state.position_m[2])
        states.append(state)
    return np.array(times), np.array(heights), states


def test_free_fall_motors_off_follows_quadratic_drag_solution() -> None:
    t, z, _ = _free_fall_from_10m()
    airborne = z > 0.0
    terminal = math.sqrt(MASS_KG * G / DRAG)
    exact = 10.0 - terminal**2 / G * np.log(np.cosh(G * t / terminal))
    vacuum = 10.0 - 0.5 * G * t**2
    assert np.max(np.abs(z[airborne] - exact[airborne])) < 1e-6
    # Drag only slows the fall, and by no more than |a_drag| <= c (g t)^2 / m integrates to.
    slower_by = z[airborne] - vacuum[airborne]
    assert np.all(slower_by >= -1e-12)
    assert np.all(slower_by <= DRAG * G**2 * t[airborne] ** 4 / (12.0 * MASS_KG) + 1e-9)


def test_free_fall_motors_off_lands_and_rests_at_zero() -> None:
    t, z, states = _free_fall_from_10m()
    assert np.all(z >= 0.0)
    # Touchdown where ln cosh(g t / v_t) = g z0 / v_t^2, i.e. cosh(...) = e for these numbers.
    terminal = math.sqrt(MASS_KG * G / DRAG)
    t_hit = math.acosh(math.exp(G * 10.0 / terminal**2)) * terminal / G
    first_contact = t[np.argmax(z == 0.0)]
    assert first_contact == pytest.approx(t_hit, abs=2e-3)
    after = [s for s in states if s.time_s > t_hit + 0.01]
    assert after and all(s.on_ground and s.position_m[2] == 0.0 for s in after)
    assert all(not np.any(s.velocity_m_s) and not np.any(s.body_rates_rad_s) for s in after)


def test_mixer_positive_moments_spin_the_flightgoggles_motors() -> None:
    loop = RateLoop(QuadrotorParams())
    hover = 9.81
    m1, m2, m3, m4 = loop.mix(0.01, 0.0, 0.0, hover)  # +roll: left motors 1, 2 faster
    assert min(m1, m2) > max(m3, m4)
    m1, m2, m3, m4 = loop.mix(0.0, 0.01, 0.0, hover)  # +pitch (nose down): rear motors 2, 3 faster
    assert min(m2, m3) > max(m1, m4)
    m1, m2, m3, m4 = loop.mix(0.0, 0.0, 0.01, hover)  # +yaw: reaction of motors 2, 4
    assert min(m2, m4) > max(m1, m3)


def test_mixer_extreme_demand_clamps_rotors_to_range() -> None:
    speeds = RateLoop(QuadrotorParams()).mix(1e3, -1e3, 1e3, 1e6)
    assert all(0.0 <= w <= 2200.0 for w in speeds)


@pytest.mark.parametrize("axis", [0, 1, 2])
def test_rate_command_step_body_rate_tracks_command(axis: int) -> None:
    sim = QuadrotorSim(noise=False, initial_position_m=(0.0, 0.0, 50.0), rotors_at_hover=True)
    rates = [0.0, 0.0, 0.0]
    rates[axis] = 1.0
    sim.set_command(RateThrustCommand((rates[0], rates[1], rates[2]), 9.81))
    sim.advance(1.5)
    measured = sim.state.body_rates_rad_s
    assert measured[axis] == pytest.approx(1.0, abs=0.05)
    assert np.all(np.abs(np.delete(measured, axis)) < 0.05)


def test_advance_fractional_durations_carry_the_remainder() -> None:
    sim = QuadrotorSim(noise=False)
    assert sim.advance(0.0005) == 0
    assert sim.advance(0.0005) == 1
    assert sim.advance(0.02) == 20
    assert sum(sim.advance(1.0 / 3.0) for _ in range(3)) == 1000
    assert sim.time_s == pytest.approx(1.021)


@pytest.mark.parametrize(
    ("make", "field"),
    [
        (lambda: RateThrustCommand((math.nan, 0.0, 0.0), 9.8), "body_rates_rad_s"),
        (lambda: RateThrustCommand((0.0, 0.0, 0.0), math.inf), "thrust_n"),
        (lambda: RateThrustCommand((0.0, 0.0), 9.8), "body_rates_rad_s"),  # type: ignore[arg-type]
        (lambda: MotorSpeedCommand((0.0, -math.inf, 0.0, 0.0)), "rotor_speeds_rad_s"),
    ],
)
def test_command_non_finite_raises_value_error_naming_field(make, field: str) -> None:
    with pytest.raises(ValueError, match=field):
        make()


def test_set_command_forced_nan_raises_and_keeps_previous_command() -> None:
    sims = [QuadrotorSim(noise=False, rotors_at_hover=True, initial_position_m=(0, 0, 3)) for _ in range(2)]
    good = RateThrustCommand((0.2, 0.0, 0.0), 11.0)
    bad = RateThrustCommand((0.0, 0.0, 0.0), 5.0)
    object.__setattr__(bad, "thrust_n", math.nan)  # bypasses validation, as a buggy caller might
    for sim in sims:
        sim.set_command(good)
    with pytest.raises(ValueError, match="thrust_n"):
        sims[0].set_command(bad)
    for sim in sims:
        sim.advance(0.5)
    assert np.array_equal(sims[0].state.position_m, sims[1].state.position_m)
    assert np.array_equal(sims[0].state.attitude_wxyz, sims[1].state.attitude_wxyz)


def test_noise_same_seed_replays_and_other_seed_differs() -> None:
    def run(seed: int) -> np.ndarray:
        sim = QuadrotorSim(
            rng=np.random.default_rng(seed), initial_position_m=(0, 0, 3), rotors_at_hover=True
        )
        sim.advance(0.3)
        sim.advance(0.2)
        return sim.state.position_m

    assert np.array_equal(run(7), run(7))
    assert not np.array_equal(run(7), run(8))


def test_constructor_noise_without_rng_raises() -> None:
    with pytest.raises(ValueError, match="rng"):
        QuadrotorSim(noise=True)


def test_constructor_low_physics_rate_raises() -> None:
    with pytest.raises(ValueError, match="physics_rate_hz"):
        QuadrotorSim(noise=False, physics_rate_hz=96.0)


def test_params_defaults_are_the_flightgoggles_drone() -> None:
    p = QuadrotorParams()
    assert (p.mass_kg, p.arm_length_m, p.inertia_kg_m2) == (1.0, 0.08, (0.0049, 0.0049, 0.0069))
    assert (p.thrust_coeff_n_per_rad_s2, p.torque_coeff_nm_per_rad_s2) == (1.91e-6, 2.6e-7)
    assert (p.motor_time_constant_s, p.max_rotor_speed_rad_s, p.drag_coeff_n_per_m_s2) == (0.02, 2200.0, 0.1)
    assert p.hover_rotor_speed_rad_s == pytest.approx(math.sqrt(9.81 / (4 * 1.91e-6)))


@pytest.mark.parametrize("field", ["mass_kg", "motor_time_constant_s", "max_rotor_speed_rad_s"])
def test_params_non_positive_value_raises(field: str) -> None:
    with pytest.raises(ValueError, match=field):
        dataclasses.replace(QuadrotorParams(), **{field: 0.0})  # type: ignore[arg-type]


def test_params_negative_inertia_raises() -> None:
    with pytest.raises(ValueError, match="inertia_kg_m2"):
        QuadrotorParams(inertia_kg_m2=(0.0049, -0.0049, 0.0069))


def test_state_arrays_are_read_only_copies() -> None:
    sim = QuadrotorSim(noise=False)
    state = sim.state
    with pytest.raises(ValueError):
        state.position_m[0] = 1.0
    sim.set_command(RateThrustCommand((0.0, 0.0, 0.0), 15.0))
    sim.advance(0.5)
    assert state.position_m[2] == 0.0 and sim.state.position_m[2] > 0.0


def test_quaternion_long_tumbling_flight_stays_unit() -> None:
    rng = np.random.default_rng(123)
    sim = QuadrotorSim(
        rng=np.random.default_rng(4), initial_position_m=(0.0, 0.0, 500.0), rotors_at_hover=True
    )
    worst = 0.0
    for _ in range(600):  # 30 s, a new random command every 50 ms
        sim.set_command(RateThrustCommand(tuple(rng.uniform(-10.0, 10.0, 3)), float(rng.uniform(5.0, 15.0))))
        for _ in range(50):
            sim.step()
            worst = max(worst, abs(float(np.linalg.norm(sim.state.attitude_wxyz)) - 1.0))
    assert worst < 1e-9
