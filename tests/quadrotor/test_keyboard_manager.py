"""The drone's keyboard_manager_node in fly.launch (ref §3.7): arrow keys → /uav/input/position.

Keys go in where a browser tab's do: the lab's KeyboardDevice (``lab.keyboard``), through the
``keyboard`` node and /keydown. Mapping: RIGHT +x, LEFT -x, UP +y, DOWN -y, 1 m per press, from (0, 0, 3).
"""

from __future__ import annotations

import numpy as np
import pytest

from node_runtime.msgs import Key, PoseStamped, Vector3
from server.world.lab import Lab

from .conftest import Probe, make_lab, node, start

POSITION = "/uav/input/position"
TAB = "tab-1"


def _press(lab: Lab, code: int, hold_s: float = 0.02) -> None:
    """Key down, hold, key up; the clock moves by ``hold_s`` and everything published is delivered."""
    now = lab.bus.clock.now()
    lab.keyboard.key_down(code, 0, TAB)
    lab.executor.spin_until(now + hold_s)
    lab.keyboard.key_up(code, 0, TAB)
    lab.executor.spin_until(now + 2 * hold_s)


def _setpoints(probe: Probe, after_s: float = -np.inf) -> list[tuple[float, float, float]]:
    return probe.vectors(POSITION, after_s)


@pytest.fixture
def adopt() -> tuple[Lab, Probe]:
    lab = make_lab()
    probe = start(lab, {POSITION: Vector3, "/uav/sensors/gps": PoseStamped})
    lab.executor.spin_until(1.0)
    return lab, probe


@pytest.fixture
def lab_mode() -> tuple[Lab, Probe]:
    lab = make_lab(keyboard_mode="lab")
    probe = start(lab, {POSITION: Vector3})
    lab.executor.spin_until(1.0)
    return lab, probe


def test_keyboard_arrows_move_setpoint_1m_in_the_documented_directions(adopt: tuple[Lab, Probe]) -> None:
    lab, probe = adopt
    seen = []
    for code in (Key.KEY_RIGHT, Key.KEY_UP, Key.KEY_LEFT, Key.KEY_LEFT, Key.KEY_DOWN, Key.KEY_DOWN):
        _press(lab, code)
        seen.append(_setpoints(probe)[-1])
    assert seen == [
        (1.0, 0.0, 3.0),
        (1.0, 1.0, 3.0),
        (0.0, 1.0, 3.0),
        (-1.0, 1.0, 3.0),
        (-1.0, 0.0, 3.0),
        (-1.0, -1.0, 3.0),
    ]
    assert node(lab, "position_controller_node").setpoint_m == (-1.0, -1.0, 3.0)


def test_keyboard_arrows_drone_flies_to_the_new_setpoint(adopt: tuple[Lab, Probe]) -> None:
    lab, probe = adopt
    _press(lab, Key.KEY_RIGHT)
    _press(lab, Key.KEY_UP)
    lab.executor.spin_until(10.0)
    assert np.abs(probe.positions(after_s=8.0)[:, 1:] - (1.0, 1.0, 3.0)).max() < 0.1


def test_keyboard_adopt_mode_moves_from_a_setpoint_published_by_someone_else(
    adopt: tuple[Lab, Probe],
) -> None:
    lab, probe = adopt
    lab.publish(POSITION, {"x": 5.0, "y": 5.0, "z": 10.0}, None)
    lab.executor.spin_until(2.0)
    _press(lab, Key.KEY_RIGHT)
    assert _setpoints(probe)[-1] == (6.0, 5.0, 10.0)
    assert node(lab, "position_controller_node").setpoint_m == (6.0, 5.0, 10.0)


def test_keyboard_adopt_mode_publishes_only_on_arrow_presses(adopt: tuple[Lab, Probe]) -> None:
    lab, probe = adopt
    lab.executor.spin_until(5.0)
    assert _setpoints(probe) == []  # nothing while no key is pressed
    _press(lab, Key.KEY_RIGHT)
    _press(lab, Key.KEY_A)  # not an arrow: no setpoint
    _press(lab, Key.KEY_SPACE)
    lab.executor.spin_until(8.0)
    _press(lab, Key.KEY_UP)
    lab.executor.spin_until(12.0)
    assert _setpoints(probe) == [(1.0, 0.0, 3.0), (1.0, 1.0, 3.0)]


def test_keyboard_adopt_mode_held_key_moves_once_no_auto_repeat(adopt: tuple[Lab, Probe]) -> None:
    lab, probe = adopt
    lab.keyboard.key_down(Key.KEY_RIGHT, 0, TAB)
    for _ in range(10):  # the browser's auto-repeat keydowns while the key is held
        lab.executor.spin_for(0.05)
        lab.keyboard.key_down(Key.KEY_RIGHT, 0, TAB)
    lab.keyboard.key_up(Key.KEY_RIGHT, 0, TAB)
    lab.executor.spin_for(0.05)
    assert _setpoints(probe) == [(1.0, 0.0, 3.0)]


def test_keyboard_lab_mode_publishes_at_20hz_from_0_0_3(lab_mode: tuple[Lab, Probe]) -> None:
    lab, probe = lab_mode
    lab.executor.spin_until(10.0)
    stamps = probe.times(POSITION)
    assert len(stamps) == 200  # every 50 ms from t = 0.05 to 10.0
    assert np.diff(stamps) == pytest.approx(0.05, abs=1e-9)
    assert set(_setpoints(probe)) == {(0.0, 0.0, 3.0)}


def test_keyboard_lab_mode_arrow_moves_setpoint_on_the_next_tick(lab_mode: tuple[Lab, Probe]) -> None:
    lab, probe = lab_mode
    _press(lab, Key.KEY_RIGHT)
    lab.executor.spin_for(0.06)
    assert _setpoints(probe)[-1] == (1.0, 0.0, 3.0)
    _press(lab, Key.KEY_UP)
    lab.executor.spin_for(0.06)
    assert _setpoints(probe)[-1] == (1.0, 1.0, 3.0)


def test_keyboard_lab_mode_overrides_setpoints_from_others(lab_mode: tuple[Lab, Probe]) -> None:
    lab, probe = lab_mode
    lab.publish(POSITION, {"x": 5.0, "y": 5.0, "z": 10.0}, None)
    lab.executor.spin_for(0.06)  # one keyboard manager tick
    assert node(lab, "position_controller_node").setpoint_m == (0.0, 0.0, 3.0)
    lab.executor.spin_for(5.0)
    assert _setpoints(probe)[-1] == (0.0, 0.0, 3.0)


def test_keyboard_lab_mode_two_keys_in_one_tick_only_the_last_counts(lab_mode: tuple[Lab, Probe]) -> None:
    lab, probe = lab_mode
    lab.executor.spin_until(1.001)  # just after a tick
    _press(lab, Key.KEY_RIGHT, hold_s=0.005)
    _press(lab, Key.KEY_UP, hold_s=0.005)  # both within the same 50 ms
    lab.executor.spin_for(0.2)
    assert _setpoints(probe)[-1] == (0.0, 1.0, 3.0)
