"""What the rocket's scene sends the pages (each update makes every open page draw its 3D view):
the rocket's pose when it moved visibly, its readouts at most every READOUT_PERIOD_S, and a
change of phase, status or countdown at once; a readout held back is sent at the next redraw."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from server.peripherals.viewer.display import Display
from server.peripherals.viewer.rocket_view import (
    MOVE_MIN_M,
    READOUT_PERIOD_S,
    RocketScene,
    RocketTracker,
    display_height,
)


@pytest.fixture
def scene() -> Iterator[RocketScene]:
    display = Display()
    try:
        yield RocketScene(display, lambda: None)
    finally:
        display.stop()


def launched(altitude_m: float, cmd_vel_m_s: float) -> RocketTracker:
    return RocketTracker(phase="launched", countdown=0, cmd_vel_m_s=cmd_vel_m_s, altitude_m=altitude_m)


def test_rocket_readouts_at_most_five_a_second_and_the_last_one_is_sent(scene: RocketScene) -> None:
    scene.draw(launched(100.0, 50.0), now_s=0.0)
    assert (scene.altitude.value, scene.cmd_vel.value, scene.stale) == (100.0, 50.0, False)

    scene.draw(launched(105.0, 51.0), now_s=READOUT_PERIOD_S / 2)  # too soon: held back
    assert (scene.altitude.value, scene.cmd_vel.value, scene.stale) == (100.0, 50.0, True)
    assert scene.label.text == "launched  100 m"

    scene.draw(launched(105.0, 51.0), now_s=READOUT_PERIOD_S)  # the next redraw sends it
    assert (scene.altitude.value, scene.cmd_vel.value, scene.stale) == (105.0, 51.0, False)
    assert scene.label.text == "launched  105 m"


def test_rocket_a_change_of_phase_is_shown_at_once(scene: RocketScene) -> None:
    scene.draw(launched(100.0, 50.0), now_s=0.0)
    failed = launched(101.0, 50.0)
    failed.phase = "abort failed"
    scene.draw(failed, now_s=0.01)
    assert scene.status.content == "**Abort Failed: the rocket had already launched.**"
    assert scene.altitude.value == 101.0 and not scene.stale


def test_rocket_pose_sent_only_when_it_moved_visibly(scene: RocketScene) -> None:
    scene.draw(launched(200_000.0, 1684.0), now_s=0.0)
    z0 = scene.rocket.position[2]
    # 100 km up the display squeezes a second's climb to well under MOVE_MIN_M.
    step = display_height(200_001.7) - display_height(200_000.0)
    assert 0 < step < MOVE_MIN_M
    scene.draw(launched(200_001.7, 1684.0), now_s=1.0)
    assert scene.rocket.position[2] == z0
    # Low down a climb of a metre moves it a metre or so: sent.
    scene.draw(launched(1.0, 10.0), now_s=2.0)
    assert scene.rocket.position[2] == pytest.approx(0.3 + display_height(1.0))
    assert scene.rocket.position[2] < z0


def test_rocket_back_on_its_pad_is_drawn_whole_at_once(scene: RocketScene) -> None:
    scene.draw(launched(100.0, 50.0), now_s=0.0)
    scene.forget_drawn()
    scene.draw(RocketTracker(), now_s=0.01)
    assert scene.status.content == "**Ready for countdown**"
    assert scene.altitude.value == 0.0
    assert scene.rocket.position[2] == pytest.approx(0.3)
