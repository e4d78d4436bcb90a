"""Setpoints a student may get wrong: outside the arena (clamped), NaN, infinite or absurd (dropped), wild."""

from __future__ import annotations

import logging
import math

import numpy as np
import pytest

from server.bus import Node
from server.lab import Lab
from server.msgs import Vector3

from .conftest import FLY_NO_NOISE, Probe, make_lab, node, start

POSITION = "/uav/input/position"


def _publisher(lab: Lab, topic: str = POSITION) -> object:
    """A student's node publishing straight on the bus, past the API's checks."""
    with lab.bus.activate():
        student = Node("student")
    return student.create_publisher(Vector3, topic, 10)


def _all_nodes_active(lab: Lab) -> bool:
    return all(n.state == "active" for n in lab.bus.nodes)


@pytest.mark.parametrize(
    ("asked", "bound"),
    [((50.0, 0.0, 3.0), (10.0, 0.0, 3.0)), ((-50.0, -20.0, 3.0), (-10.0, -10.0, 3.0)),
     ((0.0, 0.0, 40.0), (0.0, 0.0, 15.0))],
)  # fmt: skip
def test_setpoint_outside_arena_clamped_drone_settles_at_the_bound_with_warning(
    asked: tuple[float, float, float], bound: tuple[float, float, float], caplog: pytest.LogCaptureFixture
) -> None:
    lab = make_lab(FLY_NO_NOISE)
    probe = start(lab)
    lab.executor.spin_until(5.0)
    with caplog.at_level(logging.WARNING):
        lab.publish(POSITION, dict(zip("xyz", asked)), None)
        lab.executor.spin_until(5.1)
    warnings = [r.getMessage() for r in caplog.records if r.levelno == logging.WARNING]
    assert any("outside the arena" in w and "position_controller_node" in w for w in warnings)
    assert node(lab, "position_controller_node").setpoint_m == pytest.approx(bound)
    lab.executor.spin_until(20.0)
    p = probe.positions(after_s=15.0)[:, 1:]
    assert np.abs(p - bound).max() < 0.1
    beyond_m = np.abs(probe.positions()[:, 1:]) - np.array([10.0, 10.0, 15.0])
    assert beyond_m.max() < 0.2  # it never flew far out of the arena on the way


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf, 1e9])
def test_setpoint_non_finite_on_bus_dropped_with_warning_drone_keeps_old_setpoint(
    bad: float, caplog: pytest.LogCaptureFixture
) -> None:
    lab = make_lab(FLY_NO_NOISE)
    probe = start(lab)
    pub = _publisher(lab)
    pub.publish(Vector3(x=2.0, y=-2.0, z=4.0))  # type: ignore[attr-defined]
    lab.executor.spin_until(3.0)
    with caplog.at_level(logging.WARNING):
        pub.publish(Vector3(x=bad, y=1.0, z=5.0))  # type: ignore[attr-defined]
        lab.executor.spin_until(3.1)
    assert any("setpoint dropped" in r.getMessage() for r in caplog.records if r.levelno == logging.WARNING)
    assert node(lab, "position_controller_node").setpoint_m == (2.0, -2.0, 4.0)
    lab.executor.spin_until(15.0)
    assert np.abs(probe.positions(after_s=12.0)[:, 1:] - (2.0, -2.0, 4.0)).max() < 0.1
    assert _all_nodes_active(lab)


@pytest.mark.parametrize("bad", [math.nan, math.inf, 1e9])
def test_velocity_setpoint_non_finite_on_bus_dropped_drone_keeps_old_velocity(
    bad: float, caplog: pytest.LogCaptureFixture
) -> None:
    lab = make_lab(FLY_NO_NOISE)
    probe = start(lab)
    lab.executor.spin_until(5.0)
    node(lab, "position_controller_node").destroy_node()
    pub = _publisher(lab, "/uav/input/velocity")
    pub.publish(Vector3(x=0.5, y=0.0, z=0.0))  # type: ignore[attr-defined]
    lab.executor.spin_until(6.0)
    with caplog.at_level(logging.WARNING):
        pub.publish(Vector3(x=bad, y=bad, z=bad))  # type: ignore[attr-defined]
        lab.executor.spin_until(6.1)
    assert any("velocity setpoint dropped" in r.getMessage() for r in caplog.records)
    lab.executor.spin_until(10.0)
    v = probe.velocities(after_s=8.0)[:, 1:]
    assert np.all(np.isfinite(v))
    assert np.abs(v - (0.5, 0.0, 0.0)).max() < 0.05
    assert _all_nodes_active(lab)


def test_publish_through_lab_non_finite_refused_nothing_published() -> None:
    lab = make_lab()
    lab.start_nodes()
    before = lab.bus.get_topic(POSITION).publish_count
    for bad in (math.nan, math.inf, 1e9):
        with pytest.raises(ValueError):
            lab.publish(POSITION, {"x": bad, "y": 0.0, "z": 3.0}, None)
    assert lab.bus.get_topic(POSITION).publish_count == before


def _wild_setpoints(lab: Lab, rng: np.random.Generator, rate_hz: float) -> None:
    """A node publishing a random setpoint every controller tick: mostly in the arena, some far out,
    a few NaN or infinite."""
    pub = _publisher(lab)

    def tick() -> None:
        xyz = rng.uniform((-30.0, -30.0, -10.0), (30.0, 30.0, 40.0))
        roll = rng.random()
        if roll < 0.02:
            xyz[rng.integers(3)] = rng.choice([math.nan, math.inf, -math.inf])
        elif roll < 0.03:
            xyz[rng.integers(3)] = rng.choice([1e9, -1e9])
        pub.publish(Vector3(x=float(xyz[0]), y=float(xyz[1]), z=float(xyz[2])))  # type: ignore[attr-defined]

    pub.node.create_timer(1.0 / rate_hz, tick)  # type: ignore[attr-defined]


@pytest.mark.parametrize("launch", ["fly", FLY_NO_NOISE], ids=["noise", "no_noise"])
def test_wild_setpoints_every_tick_for_60s_state_stays_finite_above_ground_and_bounded(
    launch: str, caplog: pytest.LogCaptureFixture
) -> None:
    caplog.set_level(logging.ERROR, logger="node")  # 50 clamp warnings a second: tested above, costly here
    lab = make_lab(launch)
    probe = start(lab)
    _wild_setpoints(lab, np.random.default_rng(20251), rate_hz=50.0)
    lab.executor.spin_until(60.0)

    assert len(probe.got[POSITION]) >= 2999
    p = probe.positions()
    assert len(p) == 6001
    assert np.all(np.isfinite(p))
    assert p[:, 3].min() >= 0.0
    assert np.abs(p[:, 1:3]).max() < 15.0 and p[:, 3].max() < 20.0
    v = probe.velocities()[:, 1:]
    assert np.all(np.isfinite(v))
    assert np.linalg.norm(v, axis=1).max() < 30.0
    q = np.array(
        [
            (m.pose.orientation.w, m.pose.orientation.x, m.pose.orientation.y, m.pose.orientation.z)
            for _, m in probe.got["/uav/sensors/gps"]
        ]
    )
    assert np.abs(np.linalg.norm(q, axis=1) - 1.0).max() < 1e-6
    attitude = np.array(probe.vectors("/uav/sensors/attitude"))
    assert np.all(np.isfinite(attitude))
    assert _all_nodes_active(lab)


def test_wild_setpoints_recovers_to_hover_once_they_stop(caplog: pytest.LogCaptureFixture) -> None:
    caplog.set_level(logging.ERROR, logger="node")
    lab = make_lab(FLY_NO_NOISE)
    probe: Probe = start(lab)
    _wild_setpoints(lab, np.random.default_rng(7), rate_hz=50.0)
    lab.executor.spin_until(20.0)
    node(lab, "student").destroy_node()
    lab.publish(POSITION, {"x": 0.0, "y": 0.0, "z": 3.0}, None)
    lab.executor.spin_until(50.0)
    xy_after_10s = probe.positions(after_s=30.0)[:, 1:3]
    assert np.abs(xy_after_10s).max() < 0.1
    # z is slower: the velocity loop's z integral winds up against the thrust limits while the
    # setpoints are wild, and bleeds off with tau = kp_z / ki_z (about 13 s).
    z_after_10s = probe.positions(after_s=30.0, until_s=31.0)[:, 3]
    z_after_25s = probe.positions(after_s=45.0)[:, 3]
    assert np.abs(z_after_10s - 3.0).max() < 0.3
    assert np.abs(z_after_25s - 3.0).max() < 0.1
