"""The parser's public entry points on the lab's fly.launch, and the errors that concern the top-level file."""

from __future__ import annotations

from pathlib import Path

import pytest
from launchfiles import FindShare, file_error_of

from server.services.launch.description import LaunchFileError, SourceLocation
from server.services.launch.xml_parser import parse_launch_file


@pytest.fixture
def fly(share_dir: Path) -> Path:
    """The lab's fly.launch after checkpoint 3, reconstructed from the lab text."""
    return share_dir / "flightcontroller" / "launch" / "fly.launch"


def test_fly_launch_checkpoint3_flattens_includes_in_document_order(fly: Path, find_share: FindShare) -> None:
    description = parse_launch_file(fly, find_package_share=find_share)

    assert [(n.pkg, n.exec, n.name) for n in description.nodes] == [
        ("visualizer", "gui_controller.py", "GUI_Controller_Node"),
        ("flightcontroller", "position_controller.py", "position_controller_node"),
        ("sensor_simulation", "down_facing_camera.py", "down_facing_camera_node"),
        ("sensor_simulation", "pressure.py", "pressure_node"),
        ("simple_sim", "simple_sim_node", None),
        ("simple_control", "keyboard_manager", "keyboard_manager_node"),
        ("keyboard", "keyboard", "keyboard"),
    ]
    assert all(n.output == "screen" for n in description.nodes)
    assert all(n.namespace is None and not n.respawn for n in description.nodes)


def test_fly_launch_params_typed_as_launched(fly: Path, find_share: FindShare) -> None:
    nodes = {n.name: n for n in parse_launch_file(fly, find_package_share=find_share).nodes}

    gains = nodes["position_controller_node"].parameters
    assert gains == (("gains/stable/p", 1), ("gains/stable/i", 0), ("gains/stable/d", 0.3))
    assert [type(value) for _, value in gains] == [int, int, float]
    assert nodes["down_facing_camera_node"].parameters == (("image_path", "construction.jpeg"),)


def test_fly_launch_sim_node_on_exit_shutdown_ends_launch(fly: Path, find_share: FindShare) -> None:
    nodes = parse_launch_file(fly, find_package_share=find_share).nodes

    assert [n.exec for n in nodes if n.shutdown_on_exit] == ["simple_sim_node"]


def test_fly_launch_locations_point_into_each_file(fly: Path, find_share: FindShare, share_dir: Path) -> None:
    description = parse_launch_file(fly, find_package_share=find_share)

    view = str(share_dir / "visualizer" / "launch" / "view.launch")
    assert description.nodes[0].location == SourceLocation(view, 3)
    assert description.nodes[-1].location == SourceLocation(str(fly), 17)
    assert description.files == (
        str(fly),
        view,
        str(share_dir / "flightcontroller" / "launch" / "position.launch"),
        str(share_dir / "sensor_simulation" / "launch" / "sensors.launch"),
    )
    assert dict(description.args) == {}


def test_error_str_is_file_line_problem() -> None:
    error = LaunchFileError("a.launch", 3, "boom")

    assert (str(error), error.file, error.line, error.problem) == ("a.launch:3: boom", "a.launch", 3, "boom")


def test_missing_top_level_file_reported(tmp_path: Path, find_share: FindShare) -> None:
    error = file_error_of(tmp_path / "nope.launch", find_share)

    assert error.line == 0 and "not found" in error.problem
