"""GUI_Controller_Node without a display (ref §3.5): it still counts the frames it would draw: at
30 Hz while the drone moves, and only now and then while it hovers (its jitter is a millimetre or two)."""

from __future__ import annotations

import math

import pytest

from .conftest import Flight, make_lab, node, start

VIEW = "GUI_Controller_Node"


def test_view_node_no_display_draws_at_30hz_while_drone_flies() -> None:
    lab = make_lab()
    start(lab)
    view = node(lab, VIEW)
    assert view.scene is None
    lab.executor.spin_until(8.0)
    lab.publish("/uav/input/position", {"x": 5.0, "y": 5.0, "z": 10.0}, None)
    lab.executor.spin_until(8.5)  # under way
    before = view.frames_drawn
    lab.executor.spin_until(10.5)  # still flying: a 7 m trip takes longer than 2.5 s
    assert (view.frames_drawn - before) / 2.0 == pytest.approx(30.0, abs=0.6)


def test_view_node_hovering_drone_is_drawn_only_when_it_has_moved_2cm() -> None:
    lab = make_lab()
    start(lab)
    view = node(lab, VIEW)
    gps = lab.bus.get_topic("/uav/sensors/gps")
    lab.executor.spin_until(10.0)  # taken off, hovering at (0, 0, 3)
    pose = lambda: (gps.latest.pose.position, gps.latest.pose.orientation)  # noqa: E731
    drawn, last = None, view.frames_drawn
    changes = []  # (moved m, turned rad) since the last pose drawn, at each new drawing
    t = 10.0
    while t < 40.0:
        t += 1 / 30
        lab.executor.spin_until(t)
        if view.frames_drawn == last:
            continue
        last = view.frames_drawn
        p, q = pose()
        if drawn is not None:  # from the second drawing on: what changed since the one before
            p0, q0 = drawn
            dot = abs(q.w * q0.w + q.x * q0.x + q.y * q0.y + q.z * q0.z)
            changes.append((math.dist((p.x, p.y, p.z), (p0.x, p0.y, p0.z)), 2 * math.acos(min(1.0, dot))))
        drawn = p, q
    assert 1 <= len(changes) < 30  # against 900 at 30 Hz; the noise drifts it a few cm in 30 s
    # Each drawing follows a change worth showing (2 cm or 1 degree, less the 1/30 s between a
    # message and the 30 Hz redraw: the drone may move back a little in it).
    assert all(moved > 0.015 or turned > math.radians(0.8) for moved, turned in changes), changes


def test_view_node_no_display_stops_drawing_when_gps_stops() -> None:
    lab = make_lab()
    start(lab)
    lab.executor.spin_until(2.0)
    node(lab, "flightgoggles_uav_dynamics").destroy_node()
    lab.executor.spin_until(2.1)  # the last GPS message is drawn
    view = node(lab, VIEW)
    frames = view.frames_drawn
    assert frames >= 50  # 30 Hz from the take-off on (not while it still sat on the ground)
    lab.executor.spin_until(5.0)
    assert view.frames_drawn == frames


def test_view_node_pose_is_the_latest_gps(fly_flight: Flight) -> None:
    view = node(fly_flight.lab, VIEW)
    gps = fly_flight.lab.bus.get_topic("/uav/sensors/gps").latest
    p, q = gps.pose.position, gps.pose.orientation
    assert view.pose == ((p.x, p.y, p.z), (q.w, q.x, q.y, q.z))
    assert view.setpoint == fly_flight.TARGET_M
    assert "Setpoint** (5.00, 5.00, 10.00)" in view.telemetry_text()
