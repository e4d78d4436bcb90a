"""Hold-to-move on the drone's keyboard manager, and switching modes while it runs."""

from __future__ import annotations

import math

import pytest

from node_runtime.bus import ManualClock, Parameter
from node_runtime.msgs import Key
from server.host.settings import LabSettings, Settings
from server.world.lab import Lab


def fly(mode: str) -> Lab:
    lab = Lab(
        Settings(lab=LabSettings(launch="fly", viewer=False, launch_args={"keyboard_mode": mode})),
        ManualClock(0.0),
    )
    lab.start_nodes()
    lab.executor.spin_until(8.0)  # take off and settle at (0, 0, 3)
    return lab


def position(lab: Lab) -> tuple[float, float, float]:
    p = lab.bus.topics["/uav/sensors/gps"].latest.pose.position
    return p.x, p.y, p.z


def speed(lab: Lab) -> float:
    v = lab.bus.topics["/uav/sensors/velocity"].latest.twist.linear
    return math.sqrt(v.x**2 + v.y**2 + v.z**2)


def test_hold_right_moves_plus_x_while_held_and_stops_after_release() -> None:
    lab = fly("hold")
    x0, y0, z0 = position(lab)
    lab.keyboard.key_down(Key.KEY_RIGHT, 0, "t")
    lab.executor.spin_for(1.0)
    x1, y1, z1 = position(lab)
    assert x1 - x0 > 0.5, "it moved right while the key was held"
    assert abs(y1 - y0) < 0.1 and abs(z1 - z0) < 0.1
    lab.keyboard.key_up(Key.KEY_RIGHT, 0, "t")
    lab.executor.spin_for(3.0)
    x2 = position(lab)[0]
    assert speed(lab) < 0.1, "it came to rest"
    lab.executor.spin_for(1.0)
    assert abs(position(lab)[0] - x2) < 0.05, "and stays"
    assert x2 - x1 < 1.5, "it stops near where the key was let go, not far beyond"


def test_hold_speed_parameter_sets_the_cruise_speed() -> None:
    lab = fly("hold")
    manager = lab.bus.get_node("keyboard_manager_node")
    manager.set_parameters([Parameter("hold_speed_m_s", 1.0)])
    lab.keyboard.key_down(Key.KEY_UP, 0, "t")
    lab.executor.spin_for(4.0)
    vy = lab.bus.topics["/uav/sensors/velocity"].latest.twist.linear.y
    assert vy == pytest.approx(1.0, abs=0.2)
    lab.keyboard.key_up(Key.KEY_UP, 0, "t")


def test_hold_page_up_climbs_without_drifting() -> None:
    lab = fly("hold")
    x0, y0, z0 = position(lab)
    lab.keyboard.key_down(Key.KEY_PAGEUP, 0, "t")
    lab.executor.spin_for(1.0)
    lab.keyboard.key_up(Key.KEY_PAGEUP, 0, "t")
    lab.executor.spin_for(3.0)
    x, y, z = position(lab)
    assert z - z0 > 0.5 and abs(x - x0) < 0.1 and abs(y - y0) < 0.1


def test_release_all_from_dead_man_stops_a_hold() -> None:
    lab = fly("hold")
    lab.keyboard.key_down(Key.KEY_LEFT, 0, "browser")
    lab.executor.spin_for(1.0)
    lab.keyboard.release_all("browser")  # what the key channel does on blur, close or silence
    lab.executor.spin_for(3.0)
    assert speed(lab) < 0.1
    assert lab.bus.get_node("keyboard_manager_node").timer is None, "no hold timer left running"


def test_mode_switch_at_run_time_changes_behaviour() -> None:
    lab = fly("adopt")
    manager = lab.bus.get_node("keyboard_manager_node")
    setpoints = lab.bus.topics["/uav/input/position"]
    manager.set_parameters([Parameter("mode", "lab")])
    before = setpoints.publish_count
    lab.executor.spin_for(1.0)
    assert setpoints.publish_count - before == pytest.approx(20, abs=1), "lab mode publishes at 20 Hz"
    manager.set_parameters([Parameter("mode", "adopt")])
    before = setpoints.publish_count
    lab.executor.spin_for(1.0)
    assert setpoints.publish_count == before, "adopt mode publishes only on key presses"
    with pytest.raises(ValueError, match="mode must be one of"):
        manager.set_parameters([Parameter("mode", "turbo")])
    assert manager.mode == "adopt"
