"""The lab PID formulas and the position controller's reset-on-new-setpoint rule."""

from __future__ import annotations

import pytest

from sim.control import PID, LabPositionController


def test_pid_first_update_matches_lab_formula_with_derivative_kick() -> None:
    pid = PID(2.0, 0.5, 0.1)
    # e = 3, I = 0.03, D = (3 - 0) / 0.01 = 300.
    assert pid.update(4.0, 1.0, 0.01) == pytest.approx(2.0 * 3 + 0.5 * 0.03 + 0.1 * 300)
    # e = 2, I = 0.05, D = (2 - 3) / 0.01 = -100.
    assert pid.update(4.0, 2.0, 0.01) == pytest.approx(2.0 * 2 + 0.5 * 0.05 - 0.1 * 100)


def test_pid_reset_forgets_integral_and_previous_error() -> None:
    pid = PID(0.0, 1.0, 1.0)
    pid.update(1.0, 0.0, 0.5)
    pid.reset()
    assert (pid.integral, pid.prev_error) == (0.0, 0.0)
    assert pid.update(1.0, 0.0, 0.5) == pytest.approx(0.5 + 2.0)


def test_pid_limits_bound_integral_and_output() -> None:
    pid = PID(10.0, 1.0, integral_limit=0.2, output_limit=5.0)
    for _ in range(100):
        out = pid.update(1.0, 0.0, 0.1)
    assert pid.integral == 0.2
    assert out == 5.0
    assert pid.update(-1.0, 0.0, 0.1) == -5.0


def test_pid_non_positive_dt_raises() -> None:
    with pytest.raises(ValueError, match="dt_s"):
        PID(1.0).update(1.0, 0.0, 0.0)


def test_lab_position_new_setpoint_resets_all_three_pids() -> None:
    controller = LabPositionController(kp=1.0, ki=1.0)
    controller.update((0.0, 0.0, 0.0), 0.01)
    assert controller.pids[2].integral == pytest.approx(0.03)
    controller.set_setpoint((0.0, 0.0, 3.0 + 1e-7))  # within 1e-6: ignored, no reset
    assert controller.pids[2].integral == pytest.approx(0.03)
    assert controller.setpoint_m == (0.0, 0.0, 3.0)
    controller.set_setpoint((0.0, 2e-6, 3.0))  # beyond 1e-6 on one axis: reset all, take it
    assert [pid.integral for pid in controller.pids] == [0.0, 0.0, 0.0]
    assert controller.setpoint_m == (0.0, 2e-6, 3.0)


def test_lab_position_kp_1_output_is_position_error() -> None:
    controller = LabPositionController()
    controller.set_setpoint((5.0, 5.0, 10.0))
    assert controller.update((1.0, -2.0, 3.0), 0.01) == pytest.approx((4.0, 7.0, 7.0))
