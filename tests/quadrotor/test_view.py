"""GUI_Controller_Node without a display (ref §3.5): it still counts the frames it would draw, at 30 Hz."""

from __future__ import annotations

import pytest

from .conftest import Flight, make_lab, node, start

VIEW = "GUI_Controller_Node"


def test_view_node_no_display_draws_at_30hz_while_gps_arrives() -> None:
    lab = make_lab()
    start(lab)
    view = node(lab, VIEW)
    assert view.scene is None
    lab.executor.spin_until(5.0)
    before = view.frames_drawn
    lab.executor.spin_until(15.0)
    assert (view.frames_drawn - before) / 10.0 == pytest.approx(30.0, abs=0.2)


def test_view_node_no_display_stops_drawing_when_gps_stops() -> None:
    lab = make_lab()
    start(lab)
    lab.executor.spin_until(2.0)
    node(lab, "flightgoggles_uav_dynamics").destroy_node()
    lab.executor.spin_until(2.1)  # the last GPS message is drawn
    view = node(lab, VIEW)
    frames = view.frames_drawn
    assert frames >= 60
    lab.executor.spin_until(5.0)
    assert view.frames_drawn == frames


def test_view_node_pose_is_the_latest_gps(fly_flight: Flight) -> None:
    view = node(fly_flight.lab, VIEW)
    gps = fly_flight.lab.bus.get_topic("/uav/sensors/gps").latest
    p, q = gps.pose.position, gps.pose.orientation
    assert view.pose == ((p.x, p.y, p.z), (q.w, q.x, q.y, q.z))
    assert view.setpoint == fly_flight.TARGET_M
    assert "Setpoint** (5.00, 5.00, 10.00)" in view.telemetry_text()
