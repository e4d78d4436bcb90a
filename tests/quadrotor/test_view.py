"""GUI_Controller_Node without a display (ref §3.5): it still counts the frames it would draw: at
30 Hz while the drone moves, and only now and then while it hovers (its jitter is a millimetre or two)."""

from __future__ import annotations

import math

import numpy as np
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


def test_view_node_sends_the_3d_view_only_while_a_page_shows_it() -> None:
    """With no page connected the view node keeps its state (frames, trail, plot samples) but sends
    nothing to viser; the next ticks after a page connects send the latest frame, plots and text."""
    from server.peripherals.viewer.display import Display

    lab = make_lab()
    display = Display()
    watching = False
    display.watched = lambda: watching  # type: ignore[method-assign]  # a page connects when the test says
    lab.display = lab.bus.devices["display"] = display
    try:
        start(lab)
        view = node(lab, VIEW)
        scene = view.scene
        plots_before = [np.asarray(p.handle.data[0]).copy() for p in scene.plots]
        lab.executor.spin_until(8.0)  # taken off: many frames, none sent
        assert view.frames_drawn >= 30
        assert tuple(scene.drone.position) == (0.0, 0.0, 0.0)
        assert scene.telemetry.content.startswith("waiting")
        for plot, before in zip(scene.plots, plots_before, strict=True):
            np.testing.assert_array_equal(plot.handle.data[0], before)

        watching = True
        lab.executor.spin_until(8.0 + 1 / 30 + 1e-6)  # one redraw: the frame last drawn is sent
        (pos, wxyz) = view._drawn
        np.testing.assert_allclose(scene.drone.position, pos)
        np.testing.assert_allclose(scene.drone.wxyz, wxyz)
        assert len(np.asarray(scene.trail.points)) == len(view.trail) - 1
        lab.executor.spin_until(8.5)  # telemetry (5 Hz) and plots (4 Hz) caught up too
        assert scene.telemetry.content.startswith("**Position**")
        assert len(scene.plots[2].handle.data[0]) > 1
        assert scene.plots[2].handle.data[1][-1] > 1.0  # z: the drone has taken off
    finally:
        lab.launcher.shutdown()
        display.stop()
