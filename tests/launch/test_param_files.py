"""``<param from="file.yaml"/>``: ROS 2's parameters file for a node, read with the launch file (a
missing or broken one stops the launch before anything starts), and applied to the node it
launches in the app, which then serves the values over its parameter services."""

from __future__ import annotations

from pathlib import Path

import pytest
from launchfiles import FindShare, Write, file_error_of, only_node

from node_runtime.bus import ManualClock
from server.host.settings import LabSettings, Settings
from server.services.launch.description import LaunchFileError
from server.services.launch.evaluation import MAX_FILES_READ
from server.services.launch.xml_parser import parse_launch_file
from server.world.lab import Lab

PARAMS = """\
/**:
  ros__parameters:
    step_m: 0.5
    rate_hz: 10.0
/drones:
  manager:
    ros__parameters:
      rate_hz: 40.0
other_node:
  ros__parameters:
    step_m: 9.0
"""
MANAGER = '<node pkg="simple_control" exec="keyboard_manager" name="manager" namespace="/drones">'


def _launch(write: Write, body: str) -> Path:
    return write("pkg/launch/fly.launch", f"<launch>\n{body}\n</launch>\n")


def test_a_relative_file_is_read_from_the_launch_files_folder(write: Write, find_share: FindShare) -> None:
    write("pkg/launch/config/params.yaml", PARAMS)
    path = _launch(write, f'{MANAGER}\n  <param from="config/params.yaml"/>\n</node>')
    node = only_node(parse_launch_file(path, find_package_share=find_share))
    (loaded,) = node.parameter_files
    assert loaded.path == str(path.parent / "config" / "params.yaml")
    assert loaded.for_node("/drones/manager") == {"step_m": 0.5, "rate_hz": 40.0}


def test_dirname_and_an_absolute_path_name_the_same_file(write: Write, find_share: FindShare) -> None:
    params = write("pkg/launch/params.yaml", PARAMS)
    path = _launch(
        write,
        f'{MANAGER}\n  <param from="$(dirname)/params.yaml"/>\n</node>\n'
        f'<node pkg="simple_control" exec="keyboard_manager" name="b">\n  <param from="{params}"/>\n</node>',
    )
    first, second = parse_launch_file(path, find_package_share=find_share).nodes
    assert first.parameter_files[0].path == second.parameter_files[0].path == str(params)


@pytest.mark.parametrize(
    ("yaml_text", "problem"),
    [
        ("manager:\n  ros__parameters:\n    rate_hz: [1\n", "params.yaml:4: not valid YAML"),
        ("- just\n- a list\n", "params.yaml: not a parameters file"),
        ("manager:\n  ros__parameters:\n    rate_hz: [1, [2]]\n", "parameter 'rate_hz' has no value"),
    ],
)
def test_a_bad_file_names_the_launch_line_and_the_files_problem(
    write: Write, find_share: FindShare, yaml_text: str, problem: str
) -> None:
    write("pkg/launch/params.yaml", yaml_text)
    path = _launch(write, f'{MANAGER}\n  <param from="params.yaml"/>\n</node>')
    error = file_error_of(path, find_share)
    assert (error.file, error.line) == (str(path), 3)
    assert problem in error.problem and "\n" not in str(error)


def test_a_missing_file_and_one_outside_the_allowed_folders_read_alike(
    write: Write, find_share: FindShare, tmp_path: Path
) -> None:
    path = _launch(write, f'{MANAGER}\n  <param from="nowhere.yaml"/>\n</node>')
    error = file_error_of(path, find_share)
    assert error.line == 3 and f"parameters file not found: {path.parent / 'nowhere.yaml'}" in error.problem
    outside = tmp_path.parent / f"{tmp_path.name}-outside.yaml"
    outside.write_text(PARAMS, encoding="utf-8")
    try:
        confined = _launch(write, f'{MANAGER}\n  <param from="{outside}"/>\n</node>')
        error = file_error_of(confined, find_share, roots=(tmp_path,))
        assert f"parameters file not found: {outside}" in error.problem
        allowed = parse_launch_file(confined, find_package_share=find_share)  # unconfined, it is read
        assert only_node(allowed).parameter_files[0].path == str(outside)
    finally:
        outside.unlink()


def test_from_inside_a_named_param_is_refused(write: Write, find_share: FindShare) -> None:
    write("pkg/launch/params.yaml", PARAMS)
    path = _launch(
        write, f'{MANAGER}\n  <param name="gains">\n    <param from="params.yaml"/>\n  </param>\n</node>'
    )
    error = file_error_of(path, find_share)
    assert error.line == 4 and "put it in <node>" in error.problem


@pytest.fixture(scope="module")
def lab() -> Lab:
    lab = Lab(Settings(lab=LabSettings(launch="rocket", viewer=False)), ManualClock(0.0))
    lab.start_nodes()
    return lab


def _names(lab: Lab) -> set[str]:
    return {n.fully_qualified_name for n in lab.bus.nodes}


def test_a_launched_node_takes_its_sections_and_its_own_params_win(lab: Lab, tmp_path: Path) -> None:
    (tmp_path / "params.yaml").write_text(PARAMS, encoding="utf-8")
    path = tmp_path / "fly.launch"
    path.write_text(
        f'<launch>\n{MANAGER}\n  <param from="params.yaml"/>\n  <param name="step_m" value="2.0"/>\n</node>\n</launch>\n'
    )
    group = lab.launch_groups.launch(path, {})
    try:
        (node,) = [n for n in lab.bus.nodes if n.fully_qualified_name == "/drones/manager"]
        assert node.get_parameter("rate_hz").value == 40.0  # its own section over /**
        assert node.get_parameter("step_m").value == 2.0  # the node's <param> over the file
        assert "/drones/manager/get_parameters" in {s.srv_name for s in node.services}
    finally:
        lab.launch_groups.stop(group.id)


@pytest.mark.parametrize("broken", ["missing", "bad"])
def test_a_launch_whose_file_is_missing_or_bad_starts_nothing(lab: Lab, tmp_path: Path, broken: str) -> None:
    if broken == "bad":
        (tmp_path / "params.yaml").write_text("manager: [unclosed\n", encoding="utf-8")
    path = tmp_path / "fly.launch"
    path.write_text(
        '<launch>\n  <node pkg="sensor_simulation" exec="pressure.py" name="baro"/>\n'
        f'{MANAGER}\n  <param from="params.yaml"/>\n</node>\n</launch>\n'
    )
    before = _names(lab)
    with pytest.raises(LaunchFileError) as caught:
        lab.launch_groups.launch(path, {})
    assert caught.value.line == 4 and "params.yaml" in caught.value.problem
    assert _names(lab) == before and "/baro" not in before


def test_the_files_a_launch_reads_are_bounded_params_files_included(
    write: Write, find_share: FindShare
) -> None:
    write("pkg/launch/params.yaml", PARAMS)
    many = "\n".join('  <param from="params.yaml"/>' for _ in range(MAX_FILES_READ))
    path = _launch(write, f"{MANAGER}\n{many}\n</node>")
    error = file_error_of(path, find_share)
    assert error.line == 2 + MAX_FILES_READ and f"more than {MAX_FILES_READ} files" in error.problem
    fewer = _launch(write, f"{MANAGER}\n{many.split(chr(10), 1)[1]}\n</node>")  # one fewer: the limit itself
    assert (
        len(only_node(parse_launch_file(fewer, find_package_share=find_share)).parameter_files)
        == MAX_FILES_READ - 1
    )


def test_a_launch_value_the_descriptor_refuses_stops_that_node_with_the_reason(
    lab: Lab, tmp_path: Path
) -> None:
    path = tmp_path / "gui.launch"
    path.write_text(
        '<launch>\n  <node pkg="visualizer" exec="gui_controller.py" name="slow_gui">\n'
        '    <param name="redraw_hz" value="500.0"/>\n  </node>\n'
        '  <node pkg="visualizer" exec="gui_controller.py" name="fine_gui">\n'
        '    <param name="redraw_hz" value="10"/>\n  </node>\n</launch>\n'
    )
    group = lab.launch_groups.launch(path, {})
    try:
        refused, fine = group.describe()["nodes"]
        assert refused["state"] is None and "parameter 'redraw_hz'" in refused["error"]
        assert "out of range" in refused["error"]
        assert fine["error"] is None  # an integer for the double, taken as 10.0
        (node,) = [n for n in lab.bus.nodes if n.fully_qualified_name == "/fine_gui"]
        assert node.get_parameter("redraw_hz").value == 10.0
    finally:
        lab.launch_groups.stop(group.id)
