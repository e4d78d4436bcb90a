"""The launcher and the shipped launch files: the lab's graphs, the handout's snippet, errors."""

from __future__ import annotations

from pathlib import Path

import pytest

from node_runtime.bus import ManualClock, Node
from node_runtime.msgs import get_service_type
from server.host.settings import LabSettings, Settings
from server.services.launch.description import LaunchFileError
from server.world.lab import Lab

HANDOUT_FLY = """<?xml version="1.0"?>
<launch>
    <include file="$(find-pkg-share visualizer)/launch/view.launch">
    </include>
    <include file="$(find-pkg-share flightcontroller)/launch/position.launch"/>
    <include file="$(find-pkg-share sensor_simulation)/launch/sensors.launch"/>
    <node pkg="simple_sim" exec="simple_sim_node" output="screen" on_exit="shutdown"/>
    <node name="keyboard_manager_node" pkg="simple_control" exec="keyboard_manager" output="screen" />
    <node name="keyboard" pkg="keyboard" exec="keyboard" output="screen" />
</launch>
"""


def lab_for(launch: str, **args: str) -> Lab:
    lab = Lab(Settings(lab=LabSettings(launch=launch, viewer=False, launch_args=args)), ManualClock(0.0))
    lab.start_nodes()
    return lab


def names(lab: Lab) -> set[str]:
    return {n.fully_qualified_name for n in lab.bus.nodes if not n.get_name().startswith("_")}


def test_rocket_launch_starts_the_labs_nodes_by_their_lab_names() -> None:
    lab = lab_for("rocket")
    assert names(lab) == {
        "/RocketEngineNode",
        "/MainControllerNode",
        "/CountDownNode",
        "/keyboard",
        "/KeyboardManager",
    }
    assert all(e.error is None for e in lab.launcher.launched)


def test_all_launch_has_one_keyboard_feeding_both_managers() -> None:
    lab = lab_for("all")
    assert [n.get_name() for n in lab.bus.nodes].count("keyboard") == 1
    subscribers = {s.node.get_name() for s in lab.bus.topics["/keydown"].subscriptions}
    assert {"KeyboardManager", "keyboard_manager_node"} <= subscribers


def test_handout_fly_launch_snippet_parses_and_launches(tmp_path: Path) -> None:
    path = tmp_path / "fly.launch"
    path.write_text(HANDOUT_FLY)
    lab = lab_for("rocket")
    group = lab.launch_groups.launch(path, {})
    started = {n["name"] for n in group.describe()["nodes"]}
    assert {
        "/GUI_Controller_Node",
        "/position_controller_node",
        "/pressure_node",
        "/SimpleSimNode",
        "/keyboard_manager_node",
        "/keyboard",
    } <= started
    assert all(n["error"] is None for n in group.describe()["nodes"])
    lab.executor.spin_until(12.0)  # the lab's position controller waits 5 s, then climbs to 3 m
    assert lab.bus.topics["/uav/sensors/gps"].latest.pose.position.z == pytest.approx(3.0, abs=0.1)


def test_launch_error_names_file_line_and_problem_and_changes_nothing(tmp_path: Path) -> None:
    path = tmp_path / "broken.launch"
    path.write_text(
        '<launch>\n  <node pkg="rocketship" exec="countdown"/>\n  <node pkg="rocketship" exe="x"/>\n</launch>\n'
    )
    lab = lab_for("rocket")
    before = names(lab)
    with pytest.raises(LaunchFileError) as info:
        lab.launch_groups.launch(path, {})
    assert info.value.file == str(path) and info.value.line == 3 and "exe" in info.value.problem
    assert names(lab) == before


def test_launch_with_unknown_executable_reports_that_node_and_starts_the_rest(tmp_path: Path) -> None:
    path = tmp_path / "partial.launch"
    path.write_text(
        '<launch>\n  <node pkg="rocketship" exec="nope" name="ghost"/>\n'
        '  <node pkg="sensor_simulation" exec="pressure.py" name="baro"/>\n</launch>\n'
    )
    lab = lab_for("rocket")
    nodes = lab.launch_groups.launch(path, {}).describe()["nodes"]
    assert nodes[0]["error"] is not None and "no executable 'nope'" in nodes[0]["error"]
    assert nodes[0]["state"] is None  # never started
    assert nodes[1] == {
        "name": "/baro",
        "pkg": "sensor_simulation",
        "exec": "pressure.py",
        "error": None,
        "state": "active",
        "exit_code": None,
        "process": None,
    }


def test_stopping_a_launch_group_removes_its_nodes_and_topics(tmp_path: Path) -> None:
    path = tmp_path / "baro.launch"
    path.write_text('<launch><node pkg="sensor_simulation" exec="pressure.py" name="baro"/></launch>')
    lab = lab_for("rocket")
    group = lab.launch_groups.launch(path, {})
    assert "/uav/sensors/pressure" in lab.bus.topics
    lab.launch_groups.stop(group.id)
    assert "/baro" not in names(lab) and "/uav/sensors/pressure" not in lab.bus.topics
    with pytest.raises(LookupError):
        lab.launch_groups.stop(group.id)


def test_rocket_reset_restarts_countdown_without_touching_other_nodes() -> None:
    lab = lab_for("all", start_delay="0")
    keyboard = lab.bus.get_node("keyboard")
    lab.executor.spin_until(12.0)
    assert lab.bus.topics["/countdown"].latest.data == 0
    lab.rocket.reset()
    lab.executor.spin_until(12.5)
    assert lab.bus.topics["/countdown"].latest.data == 10
    assert lab.bus.get_node("keyboard") is keyboard, "the shared keyboard is not restarted"


def test_rocket_reset_service_restarts_countdown_like_the_rest_call() -> None:
    trigger = get_service_type("std_srvs/srv/Trigger")
    lab = lab_for("rocket", start_delay="0")
    lab.executor.spin_until(12.0)
    client = Node("student_cli", context=lab.bus).create_client(trigger, "/rocket/reset")
    future = client.call_async(trigger.Request())
    lab.executor.spin_until(12.5)
    assert future.result() == trigger.Response(success=True, message="rocket back on the pad")
    assert lab.bus.topics["/countdown"].latest.data == 10


def test_rocket_reset_service_without_a_rocket_says_so() -> None:
    trigger = get_service_type("std_srvs/srv/Trigger")
    lab = lab_for("fly")
    future = (
        Node("student_cli", context=lab.bus)
        .create_client(trigger, "/rocket/reset")
        .call_async(trigger.Request())
    )
    lab.executor.spin_until(0.1)
    assert future.result() == trigger.Response(success=False, message="no rocket in this launch")
