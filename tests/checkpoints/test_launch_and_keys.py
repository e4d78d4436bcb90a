"""Checkpoint 3's check on synthetic events: the student's launch, then arrow keys fly the drone."""

from __future__ import annotations

from server.world.checkpoints.events import Gps, KeyDown, Launch, LaunchedNode, Setpoint, Source
from server.world.checkpoints.launch_and_keys import LaunchAndKeysCheck

KEYBOARD = Source("/keyboard")
STUDENT = Source("/KeyboardManagerNode", "process 77", student=True)
NODES = (
    LaunchedNode("flightgoggles", "flightgoggles_uav_dynamics", None, False),
    LaunchedNode("keyboard", "keyboard", "keyboard", False),
    LaunchedNode("simple_control", "keyboard_manager", None, True),
)
RIGHT, UP = 275, 273


def student_launch(
    t_s: float = 0.0, *, in_workspace: bool = True, nodes: tuple[LaunchedNode, ...] = NODES
) -> Launch:
    return Launch(
        t_s, "/ws/src/drone_keys/launch/fly_keys.launch", "<launch>...</launch>", in_workspace, nodes
    )


def fly(check: LaunchAndKeysCheck, start_s: float, setpoints_by: Source = STUDENT) -> list[object]:
    met = [check.feed(Gps(start_s, (0.0, 0.0, 3.0)))]
    for i in range(1, 4):
        t = start_s + i
        met.append(check.feed(KeyDown(t, RIGHT, KEYBOARD)))
        met.append(check.feed(KeyDown(t + 0.1, UP, KEYBOARD)))
        met.append(check.feed(Setpoint(t + 0.2, (float(i), float(i), 3.0), setpoints_by)))
        met.append(check.feed(Gps(t + 0.8, (i * 0.9, i * 0.8, 3.0))))
    return [m for m in met if m is not None]


def test_launch_and_keys_workspace_launch_then_arrows_is_done() -> None:
    check = LaunchAndKeysCheck()
    assert check.feed(student_launch()) is None
    met = fly(check, 1.0)
    assert len(met) == 1
    evidence = met[0]
    assert isinstance(evidence, dict)
    assert evidence["launch_text"] == "<launch>...</launch>" and evidence["moved_m"][0] >= 2.0
    assert any(n["student"] for n in evidence["nodes"]) and evidence["track"]


def test_launch_and_keys_the_labs_fly_launch_is_not_done() -> None:
    check = LaunchAndKeysCheck()
    check.feed(student_launch(in_workspace=False))
    assert fly(check, 1.0) == []
    assert "not a file of your workspace" in check.progress(9.0)


def test_launch_and_keys_a_launch_without_the_students_node_is_not_done() -> None:
    check = LaunchAndKeysCheck()
    check.feed(student_launch(nodes=NODES[:2]))
    assert fly(check, 1.0) == []
    assert "no node of your own" in check.progress(9.0)


def test_launch_and_keys_setpoints_of_the_labs_manager_are_not_done() -> None:
    check = LaunchAndKeysCheck()
    check.feed(student_launch())
    assert fly(check, 1.0, setpoints_by=Source("/keyboard_manager")) == []


def test_launch_and_keys_moved_in_x_only_is_not_done() -> None:
    check = LaunchAndKeysCheck()
    check.feed(student_launch())
    check.feed(Gps(1.0, (0.0, 0.0, 3.0)))
    check.feed(KeyDown(2.0, RIGHT, KEYBOARD))
    check.feed(Setpoint(2.1, (3.0, 0.0, 3.0), STUDENT))
    assert check.feed(Gps(4.0, (3.0, 0.5, 3.0))) is None
    assert "0.5 m in y" in check.progress(4.0)
