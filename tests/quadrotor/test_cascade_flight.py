"""The default fly launch flown on the bus (rotor physics + cascade): take-off, hover, sensor rates, a step.

Each property holds with the dynamics node's process noise on (the default) and off.
"""

from __future__ import annotations

import numpy as np
import pytest

from .conftest import Flight

HOVER_M = np.array([0.0, 0.0, 3.0])


@pytest.fixture(params=["noise", "no_noise"])
def flight(request: pytest.FixtureRequest) -> Flight:
    return request.getfixturevalue("fly_flight" if request.param == "noise" else "quiet_flight")


def test_hover_default_setpoint_takes_off_from_the_ground(flight: Flight) -> None:
    p = flight.probe.positions(until_s=flight.STEP_AT_S)
    assert p[0, 0] == 0.0 and np.allclose(p[0, 1:], 0.0)
    assert np.all(p[:, 3] >= 0.0)
    climbed = np.nonzero(p[:, 3] > 2.9)[0]
    assert climbed.size and p[climbed[0], 0] < 4.0


def test_hover_default_setpoint_holds_3m_within_2cm_after_settling(flight: Flight) -> None:
    settled = flight.probe.positions(after_s=5.0, until_s=flight.STEP_AT_S)
    assert len(settled) > 900
    assert np.abs(settled[:, 3] - 3.0).max() < 0.02
    assert np.abs(settled[:, 1:3]).max() < 0.03


def test_hover_default_setpoint_does_not_overshoot_on_take_off(flight: Flight) -> None:
    z = flight.probe.positions(until_s=flight.STEP_AT_S)[:, 3]
    assert z.max() < 3.1


@pytest.mark.parametrize("topic", ["/uav/sensors/gps", "/uav/sensors/velocity", "/uav/sensors/attitude"])
def test_sensors_cascade_topics_publish_at_100hz(flight: Flight, topic: str) -> None:
    stamps = flight.probe.times(topic, after_s=5.0, until_s=15.0)
    rate_hz = (len(stamps) - 1) / (stamps[-1] - stamps[0])
    assert rate_hz >= 50.0
    assert rate_hz == pytest.approx(100.0, rel=0.01)
    assert np.diff(stamps).max() == pytest.approx(0.01, abs=1e-9)


def test_step_5_5_10_settles_within_10cm_by_10s_and_stays(flight: Flight) -> None:
    p = flight.probe.positions(after_s=flight.STEP_AT_S)
    error_m = np.abs(p[:, 1:] - np.array(flight.TARGET_M)).max(axis=1)
    outside = np.nonzero(error_m >= 0.1)[0]
    settle_s = p[outside[-1] + 1, 0] - flight.STEP_AT_S
    assert settle_s < 10.0
    assert p[-1, 0] - flight.STEP_AT_S >= settle_s + 5.0  # it stayed for at least 5 s after settling


def test_step_5_5_10_overshoots_less_than_half_a_metre_per_axis(flight: Flight) -> None:
    p = flight.probe.positions(after_s=flight.STEP_AT_S)[:, 1:]
    start = HOVER_M
    target = np.array(flight.TARGET_M)
    direction = np.sign(target - start)
    overshoot_m = ((p - target) * direction).max(axis=0)
    assert np.all(overshoot_m < 0.5)


def test_step_5_5_10_speed_stays_within_the_controllers_limits(flight: Flight) -> None:
    v = flight.probe.velocities(after_s=flight.STEP_AT_S)[:, 1:]
    assert np.linalg.norm(v, axis=1).max() < 10.0
