"""Setpoints a student may get wrong: outside the arena (clamped), NaN, infinite or absurd (dropped), wild."""

from __future__ import annotations

import logging
import math
from collections.abc import Iterator

import numpy as np
import pytest

from node_runtime.bus import Node
from node_runtime.msgs import Vector3
from server.world.lab import Lab

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
    [
        ((50.0, 0.0, 3.0), (10.0, 0.0, 3.0)),
        ((-50.0, -20.0, 3.0), (-10.0, -10.0, 3.0)),
        ((0.0, 0.0, 40.0), (0.0, 0.0, 15.0)),
    ],
)
def test_setpoint_outside_arena_clamped_drone_settles_at_the_bound_with_warning(
    asked: tuple[float, float, float], bound: tuple[float, float, float], caplog: pytest.LogCaptureFixture
) -> None:
    lab = make_lab(FLY_NO_NOISE)
    probe = start(lab)
    lab.executor.spin_until(5.0)
    with caplog.at_level(logging.WARNING):
        lab.publish(POSITION, dict(zip("xyz", asked, strict=True)), None)
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


class WildRun:
    """The default fly launch with a random setpoint every controller tick (50 Hz) for 60 s, then the
    wild node gone and one hover setpoint (0, 0, 3), for 30 s more."""

    WILD_UNTIL_S = 60.0
    END_S = 90.0

    def __init__(self) -> None:
        self.lab = make_lab()
        self.probe: Probe = start(self.lab)
        _wild_setpoints(self.lab, np.random.default_rng(20251), rate_hz=50.0)
        self.lab.executor.spin_until(self.WILD_UNTIL_S)
        self.wild_setpoints = len(self.probe.got[POSITION])
        self.all_active_after_wild = _all_nodes_active(self.lab)
        node(self.lab, "student").destroy_node()
        self.lab.publish(POSITION, {"x": 0.0, "y": 0.0, "z": 3.0}, None)
        self.lab.executor.spin_until(self.END_S)


@pytest.fixture(scope="module")
def wild() -> Iterator[WildRun]:
    node_log = logging.getLogger("node")
    level = node_log.level
    node_log.setLevel(logging.ERROR)  # 50 clamp warnings a second: tested above, costly here
    try:
        run = WildRun()
    finally:
        node_log.setLevel(level)
    yield run
    run.lab.launcher.shutdown()


def test_wild_setpoints_every_tick_for_60s_state_stays_finite_above_ground_and_bounded(wild: WildRun) -> None:
    assert wild.wild_setpoints == 3000
    until = wild.WILD_UNTIL_S
    p = wild.probe.positions(until_s=until)
    assert len(p) == 6001
    assert np.all(np.isfinite(p))
    assert p[:, 3].min() >= 0.0
    assert np.abs(p[:, 1:3]).max() < 15.0 and p[:, 3].max() < 20.0
    v = wild.probe.velocities(until_s=until)[:, 1:]
    assert np.all(np.isfinite(v))
    assert np.linalg.norm(v, axis=1).max() < 30.0
    q = np.array(
        [
            (m.pose.orientation.w, m.pose.orientation.x, m.pose.orientation.y, m.pose.orientation.z)
            for t, m in wild.probe.got["/uav/sensors/gps"]
            if t <= until
        ]
    )
    assert np.abs(np.linalg.norm(q, axis=1) - 1.0).max() < 1e-6
    assert np.all(np.isfinite(wild.probe.vectors("/uav/sensors/attitude")))
    assert wild.all_active_after_wild


def test_wild_setpoints_recovers_to_hover_within_10cm_10s_after_they_stop(wild: WildRun) -> None:
    """Thrust sat at its limits for much of the wild minute: the z integral must not have wound up."""
    after = wild.probe.positions(after_s=wild.WILD_UNTIL_S + 10.0)
    assert np.abs(after[:, 1:3]).max() < 0.1
    assert np.abs(after[:, 3] - 3.0).max() < 0.1
