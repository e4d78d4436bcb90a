"""The labs' camera views: which one a page with no remembered choice opens on, and what it is told."""

from __future__ import annotations

import numpy as np

from server.packages.visualizer.gui_controller import DroneScene
from server.peripherals.viewer.display import Display
from server.peripherals.viewer.views import CameraView, Follow, ViewRegistry

ROCKET = CameraView("Rocket", (71.0, -11.0, 9.0), (60.0, 0.0, 7.5))
DRONE = CameraView("Quadrotor", (0.0, -10.0, 6.0), (0.0, 0.0, 4.0), Follow("/lab/drone", (0.0, -5.0, 2.2)))


def registry(*views: CameraView) -> ViewRegistry:
    out = ViewRegistry()
    for view in views:
        out.add(view)
    return out


def test_views_lab_under_way_is_suggested_before_an_always_live_one() -> None:
    counting = CameraView(**{**ROCKET.__dict__, "busy": lambda: True})
    assert registry(DRONE, counting).suggested() == "Rocket"


def test_views_finished_lab_gives_way_to_an_always_live_one() -> None:
    launched = CameraView(**{**ROCKET.__dict__, "busy": lambda: False})
    assert registry(launched, DRONE).suggested() == "Quadrotor"


def test_views_only_a_finished_lab_is_still_suggested() -> None:
    launched = CameraView(**{**ROCKET.__dict__, "busy": lambda: False})
    assert registry(launched).suggested() == "Rocket"
    assert registry().suggested() is None


def test_views_json_carries_cameras_and_the_followed_vehicle() -> None:
    drone = CameraView(
        DRONE.name, DRONE.position, DRONE.look_at, Follow("/lab/drone", (0, -5, 2), "/lab/sp", "/lab/trail")
    )
    launched = CameraView(**{**ROCKET.__dict__, "busy": lambda: False})
    out = registry(launched, drone).to_json()
    assert out["suggested"] == "Quadrotor"
    rocket, quad = out["views"]
    assert (rocket["name"], rocket["position"], rocket["look_at"], rocket["follow"]) == (
        "Rocket",
        (71.0, -11.0, 9.0),
        (60.0, 0.0, 7.5),
        None,
    )
    assert quad["follow"] == {
        "node": "/lab/drone",
        "offset": (0, -5, 2),
        "setpoint": "/lab/sp",
        "trail": "/lab/trail",
    }


def test_drone_scene_sends_trail_newest_segment_first() -> None:
    """The page draws only the first N segments when it must draw less: they must be the newest."""
    display = Display()
    try:
        scene = DroneScene(display)
        trail = np.array([[0, 0, 1], [1, 0, 1], [2, 0, 1], [3, 0, 1]], dtype=np.float32)
        scene.draw((3.0, 0.0, 1.0), (1.0, 0.0, 0.0, 0.0), (4.0, 0.0, 1.0), trail)
        segments = np.asarray(scene.trail.points)
    finally:
        display.stop()
    assert segments.shape == (3, 2, 3)
    np.testing.assert_array_equal(segments[0], [[3, 0, 1], [2, 0, 1]])  # newest: the drone's end
    np.testing.assert_array_equal(segments[-1], [[1, 0, 1], [0, 0, 1]])
    assert "Quadrotor" in display.views
    assert display.views["Quadrotor"].follow is not None
