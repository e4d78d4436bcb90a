"""YAML launch files: ROS 2's YAML frontend read into the same model as XML, errors at YAML lines."""

from __future__ import annotations

from pathlib import Path

import pytest
from launchfiles import FindShare, Write, file_error_of

from server.host.processes.command import ros_args
from server.services.launch.launcher import with_ros_arguments
from server.services.launch.xml_parser import parse_launch_file

TUTORIAL_YAML = """\
launch:

- arg:
    name: "robot_ns"
    default: "turtlesim1"
- let:
    name: "topic"
    value: "/$(var robot_ns)/pose"

- node:
    pkg: "rocketship"
    exec: "countdown"
    name: "sim"
    namespace: "$(var robot_ns)"
    output: "screen"
    param:
    - name: "start_delay_s"
      value: 2.5
    - name: "gains"
      value: [1.0, 2.0]
    - name: "gains_named"
      value: ["a", "b"]
    - name: "limits"
      param:
      - name: "max"
        value: 3
    remap:
    - from: "/countdown"
      to: "$(var topic)"

- group:
  - push-ros-namespace:
      namespace: "grouped"
  - node:
      pkg: "rocketship"
      exec: "main_controller"
- group:
    if: "false"
    children:
    - node:
        pkg: "rocketship"
        exec: "never"
"""


def test_yaml_nodes_arguments_params_remaps_and_groups(write: Write, find_share: FindShare) -> None:
    path = write("tutorial_launch.yaml", TUTORIAL_YAML)

    description = parse_launch_file(path, args={"robot_ns": "t2"}, find_package_share=find_share)

    sim, grouped = description.nodes
    assert (sim.pkg, sim.exec, sim.name, sim.namespace, sim.output) == (
        "rocketship",
        "countdown",
        "sim",
        "/t2",
        "screen",
    )
    assert sim.parameters == (
        ("start_delay_s", 2.5),
        ("gains", [1.0, 2.0]),
        ("gains_named", ["a", "b"]),
        ("limits.max", 3),
    )
    assert sim.remappings == (("/countdown", "/t2/pose"),)
    assert (sim.location.file, sim.location.line) == (str(path), 10)
    assert (grouped.exec, grouped.name, grouped.namespace) == ("main_controller", None, "/grouped")
    assert dict(description.args) == {"robot_ns": "t2"}


def test_yaml_includes_and_is_included_by_xml_with_arguments(write: Write, find_share: FindShare) -> None:
    write("child_launch.yaml", 'launch:\n- arg: {name: "who"}\n- node: {pkg: "p", exec: "$(var who)"}\n')
    write(
        "middle.launch.xml",
        '<launch><include file="$(dirname)/child_launch.yaml">'
        '<arg name="who" value="from_xml"/></include></launch>',
    )
    top = write(
        "top_launch.yaml",
        'launch:\n- include:\n    file: "$(dirname)/middle.launch.xml"\n'
        '- include:\n    file: "child_launch.yaml"\n    arg:\n    - {name: who, value: direct}\n',
    )

    description = parse_launch_file(top, find_package_share=find_share)

    assert [n.exec for n in description.nodes] == ["from_xml", "direct"]
    assert [Path(f).name for f in description.files] == [
        "top_launch.yaml",
        "middle.launch.xml",
        "child_launch.yaml",
    ]


@pytest.mark.parametrize(
    ("text", "line", "problem"),
    [
        (
            "launch:\n- node:\n    pkg: p\n    exe: x\n",
            2,
            "unknown attribute 'exe' on <node>; did you mean 'exec'?",
        ),
        ("launch:\n- nod:\n    pkg: p\n", 2, "unknown element <nod> inside <launch>; did you mean <node>?"),
        ("launch:\n- node:\n    pkg: p\n   exec: x\n", 4, "not valid YAML"),
        ("nodes:\n- node: {pkg: p, exec: x}\n", 1, "a YAML launch file is one key, 'launch:'"),
        (
            "launch:\n- node: {pkg: p, exec: x}\n  arg: {name: a}\n",
            2,
            "each action is a mapping with one key",
        ),
        ("launch:\n- node: {pkg: p, exec: '$(var nope)'}\n", 2, "no argument or variable 'nope'"),
    ],
)
def test_yaml_errors_name_the_yaml_line(
    write: Write, find_share: FindShare, text: str, line: int, problem: str
) -> None:
    path = write("bad_launch.yaml", text)

    error = file_error_of(path, find_share)

    assert (error.file, error.line) == (str(path), line)
    assert problem in error.problem


def test_node_args_and_ros_args_reach_the_command_line(write: Write, find_share: FindShare) -> None:
    path = write(
        "args_launch.yaml",
        "launch:\n- node:\n    pkg: p\n    exec: x\n    name: n\n    args: \"--flag 'two words'\"\n"
        '    ros_args: "--log-level debug"\n',
    )

    (node,) = parse_launch_file(path, find_package_share=find_share).nodes

    assert (node.arguments, node.ros_arguments) == (("--flag", "two words"), ("--log-level", "debug"))
    lab_args = ros_args(node.name, node.namespace, node.parameters, node.remappings)
    assert [*node.arguments, *with_ros_arguments(lab_args, node.ros_arguments)] == [
        "--flag",
        "two words",
        "--ros-args",
        "-r",
        "__node:=n",
        "--log-level",
        "debug",
    ]
    assert with_ros_arguments([], node.ros_arguments) == ["--ros-args", "--log-level", "debug"]
