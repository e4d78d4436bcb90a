"""fly.launch simple:=true, the Fall 2025 lab (ref §3.3-3.4, §3.8): SimpleSimNode at 20 Hz and the
lab's position PID (Kp=1) at 100 Hz after a 5 s delay.

The assertions use the sim's true position (recorded at each GPS tick) where the lab's numbers are
about the drone, and the GPS messages where they are about what a student sees.
"""

from __future__ import annotations

import math
from collections.abc import Iterator

import numpy as np
import pytest

from node_runtime.msgs import PoseStamped

from .conftest import Probe, make_lab, node, start

STEP_AT_S = 15.0
TARGET_M = (5.0, 5.0, 10.0)


class SimpleFlight:
    def __init__(self) -> None:
        self.lab = make_lab(simple="true")
        self.probe: Probe = start(self.lab)
        sim = node(self.lab, "SimpleSimNode").sim
        self.true: list[tuple[float, ...]] = []
        self.probe.node.create_subscription(
            PoseStamped,
            "/uav/sensors/gps",
            lambda _msg: self.true.append((self.lab.bus.clock.now(), *sim.state.position_m)),
            10_000,
        )
        self.lab.executor.spin_until(STEP_AT_S)
        self.lab.publish("/uav/input/position", dict(zip("xyz", TARGET_M, strict=True)), None)
        self.lab.executor.spin_until(30.0)

    def true_at(self, t_s: float) -> np.ndarray:
        rows = np.array(self.true)
        return rows[np.argmin(np.abs(rows[:, 0] - t_s)), 1:]

    def true_rows(self, after_s: float = -math.inf, until_s: float = math.inf) -> np.ndarray:
        rows = np.array(self.true)
        return rows[(rows[:, 0] >= after_s) & (rows[:, 0] <= until_s)]


@pytest.fixture(scope="module")
def simple() -> Iterator[SimpleFlight]:
    flight = SimpleFlight()
    yield flight
    flight.lab.launcher.shutdown()


def test_simple_mode_first_5s_controller_silent_drone_stays_at_origin(simple: SimpleFlight) -> None:
    assert simple.probe.times("/uav/input/velocity")[0] > 5.0
    assert np.all(simple.true_rows(until_s=5.0)[:, 1:] == 0.0)
    gps = simple.probe.positions(until_s=5.0)[:, 1:]
    assert np.abs(gps).max() < 0.05  # GPS noise only (sigma 0.01 m)


def test_simple_mode_climb_to_3m_first_order_with_1s_time_constant(simple: SimpleFlight) -> None:
    z_1s = simple.true_at(6.0)[2]
    assert z_1s == pytest.approx(3.0 * (1.0 - math.exp(-1.0)), abs=0.1)
    assert simple.true_at(10.0)[2] == pytest.approx(2.98, abs=0.01)  # ref §3.4: 2.98 m 5 s after start
    climb = simple.true_rows(until_s=STEP_AT_S)
    assert climb[:, 3].max() < 3.01  # first order: no overshoot
    assert np.all(np.diff(climb[:, 3]) >= -0.01)


def test_simple_mode_hover_gps_noise_sigma_is_1cm(simple: SimpleFlight) -> None:
    gps = simple.probe.positions(after_s=10.0, until_s=STEP_AT_S)[:, 1:]
    true = simple.true_rows(after_s=10.0, until_s=STEP_AT_S)[:, 1:]
    assert gps.shape == true.shape
    assert np.std(gps - true, axis=0) == pytest.approx([0.01] * 3, abs=0.003)


def test_simple_mode_gps_at_20hz_controller_at_100hz(simple: SimpleFlight) -> None:
    gps = simple.probe.times("/uav/sensors/gps", after_s=5.0, until_s=15.0)
    velocity = simple.probe.times("/uav/input/velocity", after_s=5.0, until_s=15.0)
    assert (len(gps) - 1) / (gps[-1] - gps[0]) == pytest.approx(20.0, rel=0.01)
    assert (len(velocity) - 1) / (velocity[-1] - velocity[0]) == pytest.approx(100.0, rel=0.01)


def test_simple_mode_step_5_5_10_first_tick_rate_limited_to_5m_s_per_axis(simple: SimpleFlight) -> None:
    rows = simple.true_rows(after_s=STEP_AT_S - 0.05, until_s=STEP_AT_S + 0.06)
    v_before, v_after = np.diff(rows[:, 1:], axis=0)[:2] / 0.05
    dv = v_after - v_before
    assert np.abs(dv[2]) == pytest.approx(5.0, abs=1e-9)  # asked for 7 m/s up: capped
    assert np.abs(dv[:2]) == pytest.approx([5.0, 5.0], abs=0.05)  # asked for about 5: not capped


def test_simple_mode_step_5_5_10_within_5cm_in_about_5s_and_stays(simple: SimpleFlight) -> None:
    rows = simple.true_rows(after_s=STEP_AT_S)
    error_m = np.linalg.norm(rows[:, 1:] - TARGET_M, axis=1)
    outside = np.nonzero(error_m >= 0.05)[0]
    settle_s = rows[outside[-1] + 1, 0] - STEP_AT_S
    assert 4.0 <= settle_s <= 6.0
    overshoot = ((rows[:, 1:] - TARGET_M) * np.sign(np.array(TARGET_M) - (0.0, 0.0, 3.0))).max()
    assert overshoot < 0.05
