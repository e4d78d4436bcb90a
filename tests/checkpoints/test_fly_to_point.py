"""Checkpoint 2's check on synthetic events: setpoints at a rate, and the drone held at the target."""

from __future__ import annotations

from server.world.checkpoints.events import Gps, Setpoint, Source
from server.world.checkpoints.fly_to_point import FlyToPointCheck

PANEL = Source("/_page_tools")
TARGET = (5.0, 5.0, 10.0)


def fly(
    check: FlyToPointCheck, rate_hz: float, seconds: float, at: tuple[float, float, float] = TARGET
) -> list[object]:
    """Setpoints to the target at ``rate_hz`` and GPS at 20 Hz with the drone at ``at``; what was met."""
    met = []
    t, next_setpoint = 0.0, 0.0
    while t <= seconds:
        if t >= next_setpoint - 1e-9:
            met.append(check.feed(Setpoint(t, TARGET, PANEL)))
            next_setpoint += 1.0 / rate_hz
        met.append(check.feed(Gps(t, at)))
        t = round(t + 0.05, 3)
    return [m for m in met if m is not None]


def test_fly_to_point_1_hz_and_held_for_3_s_is_done() -> None:
    check = FlyToPointCheck()
    met = fly(check, 1.0, 8.0)
    assert len(met) >= 1
    evidence = met[0]
    assert isinstance(evidence, dict)
    assert evidence["publisher"] == "/_page_tools" and 0.8 <= evidence["rate_hz"] <= 1.2
    assert evidence["held_s"] >= 3.0 and evidence["track"] and len(evidence["setpoints"]) >= 5


def test_fly_to_point_5_hz_is_not_done() -> None:
    check = FlyToPointCheck()
    assert fly(check, 5.0, 12.0) == []
    assert "at 5.0 Hz" in check.progress(12.0)


def test_fly_to_point_fewer_than_5_messages_is_not_done() -> None:
    check = FlyToPointCheck()
    assert fly(check, 1.0, 3.5) == []  # 4 messages, though held 3.5 s


def test_fly_to_point_drone_elsewhere_is_not_done() -> None:
    check = FlyToPointCheck()
    assert fly(check, 1.0, 10.0, at=(5.0, 5.0, 9.5)) == []
    assert "0.5 m from (5, 5, 10)" in check.progress(10.0)


def test_fly_to_point_publisher_stopped_long_ago_is_not_done() -> None:
    check = FlyToPointCheck()
    for i in range(6):
        check.feed(Setpoint(float(i), TARGET, PANEL))
    met = [check.feed(Gps(t / 10, (9.0, 9.0, 9.0))) for t in range(60, 300)]  # far while it publishes
    met += [check.feed(Gps(t / 10, TARGET)) for t in range(300, 400)]  # there 25 s after the last one
    assert not any(met)


def test_fly_to_point_0_8_hz_is_at_the_edge_and_done() -> None:
    check = FlyToPointCheck()
    assert fly(check, 0.8, 10.0)
