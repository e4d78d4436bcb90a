"""interface.py: ``ros2 interface list|packages|package|show`` over the lab's own interfaces and a
workspace's, read from their definitions."""

from __future__ import annotations

import argparse
from collections.abc import Callable
from pathlib import Path

import pytest
from workspace.interface_packages import TUTORIAL_CMAKE, interface_package, tutorial_workspace

from server.cli import build_parser
from server.cli.client import LabClient

from .conftest import Result

NO_LAB = "http://127.0.0.1:9"  # nothing listens: these verbs read definitions, not the graph


def interface(capsys: pytest.CaptureFixture[str], *argv: str) -> Result:
    """One ``ros2lab interface`` command, run in this process."""
    args: argparse.Namespace = build_parser().parse_args(["interface", *argv])
    with LabClient(NO_LAB) as client:
        code = int(args.handler(args, client))
    out = capsys.readouterr()
    return Result(code, out.out, out.err)


@pytest.fixture
def ws(tmp_path: Path) -> Path:
    tutorial_workspace(tmp_path)
    return tmp_path


def test_show_student_message_with_constants_bounds_and_nested_types(
    capsys: pytest.CaptureFixture[str], ws: Path
) -> None:
    result = interface(capsys, "show", "fleet_interfaces/msg/Telemetry", "--workspace", str(ws))
    assert result.code == 0, result.err
    lines = result.out.splitlines()
    assert lines[:5] == [
        "# One vehicle's telemetry.",
        "uint8 MODE_IDLE=0",
        "uint8 MODE_FLYING=1",
        "int32 MAX_CODES=4",
        'string CALLSIGN_PREFIX="uav_"',
    ]
    assert 'string<=12 callsign "uav_1"' in lines and "int32[<=4] codes" in lines
    counts = lines.index("tutorial_interfaces/Num[] counts")
    assert lines[counts + 1] == "\tint64 num"  # a nested type's definition, one tab in
    assert "geometry_msgs/Point[2] corners" in lines


def test_show_student_service_and_short_name(capsys: pytest.CaptureFixture[str], ws: Path) -> None:
    result = interface(capsys, "show", "tutorial_interfaces/AddThreeInts", "--workspace", str(ws))
    assert (result.code, result.out) == (0, "int64 a\nint64 b\nint64 c\n---\nint64 sum\n"), result.err


def test_package_and_list_and_packages_name_the_students_types(
    capsys: pytest.CaptureFixture[str], ws: Path
) -> None:
    result = interface(capsys, "package", "tutorial_interfaces", "--workspace", str(ws))
    assert (result.code, result.out.split()) == (
        0,
        [
            "tutorial_interfaces/msg/Num",
            "tutorial_interfaces/msg/Sphere",
            "tutorial_interfaces/srv/AddThreeInts",
        ],
    )
    listed = interface(capsys, "list", "--workspace", str(ws)).out.splitlines()
    assert (
        listed.index("Messages:")
        < listed.index("    fleet_interfaces/msg/Telemetry")
        < listed.index("Services:")
        < listed.index("    tutorial_interfaces/srv/AddThreeInts")
    )
    assert "    std_msgs/msg/String" in listed and "    std_srvs/srv/Trigger" in listed
    assert listed.index("Actions:") < listed.index("    custom_action_interfaces/action/Fibonacci")
    assert not any("Fibonacci_" in line for line in listed)  # an action's own types are not listed
    actions = interface(capsys, "package", "custom_action_interfaces", "--workspace", str(ws))
    assert (actions.code, actions.out) == (0, "custom_action_interfaces/action/Fibonacci\n")
    shown = interface(capsys, "show", "custom_action_interfaces/action/Fibonacci", "--workspace", str(ws))
    assert shown.out == "int32 order\n---\nint32[] sequence\n---\nint32[] partial_sequence\n"
    only = interface(capsys, "list", "-s", "--workspace", str(ws)).out.splitlines()
    assert only[0] == "Services:" and "Messages:" not in only
    packages = interface(capsys, "packages", "--workspace", str(ws)).out.split()
    assert {"fleet_interfaces", "tutorial_interfaces", "std_msgs"} <= set(packages)


def test_broken_definition_is_one_line_on_stderr_exit_1_and_the_rest_listed(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    folder = tmp_path / "src/broken_interfaces"
    interface_package(
        folder,
        "broken_interfaces",
        TUTORIAL_CMAKE.replace("tutorial_", "broken_"),
        {
            "msg/Num.msg": "int64 num\nuint8 LIMIT=-1\n",
            "msg/Sphere.msg": "geometry_msgs/Point center\n",
            "srv/AddThreeInts.srv": "int64 a\n---\nint64 sum\n",
        },
    )
    problem = f"{folder / 'msg/Num.msg'}:2: -1 is out of range for uint8"
    show = interface(capsys, "show", "broken_interfaces/msg/Num", "--workspace", str(tmp_path))
    assert (show.code, show.out, show.err) == (1, "", problem + "\n")
    package = interface(capsys, "package", "broken_interfaces", "--workspace", str(tmp_path))
    assert package.code == 1 and package.err == problem + "\n"
    assert package.out.split() == ["broken_interfaces/msg/Sphere", "broken_interfaces/srv/AddThreeInts"]
    listed = interface(capsys, "list", "--workspace", str(tmp_path))
    assert (
        listed.code == 1 and listed.err == problem + "\n" and "    broken_interfaces/msg/Sphere" in listed.out
    )


def test_unknown_package_and_type_exit_1(capsys: pytest.CaptureFixture[str], ws: Path) -> None:
    result = interface(capsys, "package", "nope_interfaces", "--workspace", str(ws))
    assert (result.code, result.err) == (1, "Unknown package 'nope_interfaces'\n")
    result = interface(capsys, "show", "tutorial_interfaces/msg/Nope", "--workspace", str(ws))
    assert result.code == 1 and "tutorial_interfaces/msg/Nope" in result.err


# -- against the live server ------------------------------------------------------------------
def test_interface_list_messages_with_ros_names(ros2lab: Callable[..., Result]) -> None:
    result = ros2lab("interface", "list")
    assert result.code == 0, result.err
    lines = result.out.splitlines()
    assert lines[0] == "Messages:" and "Services:" in lines
    assert {"    geometry_msgs/msg/Vector3", "    std_msgs/msg/Int64", "    keyboard_msgs/msg/Key"} <= set(
        lines
    )


def test_interface_show_twist_as_a_msg_file(ros2lab: Callable[..., Result]) -> None:
    result = ros2lab("interface", "show", "geometry_msgs/msg/Twist")
    assert result.code == 0, result.err
    # As ROS 2's docs show it ("Understanding topics"): the .msg file's text as ROS 2 ships it, each
    # nested definition without its comments.
    assert result.out.splitlines() == [
        "# This expresses velocity in free space broken into its linear and angular parts.", "",
        "Vector3  linear", "\tfloat64 x", "\tfloat64 y", "\tfloat64 z",
        "Vector3  angular", "\tfloat64 x", "\tfloat64 y", "\tfloat64 z",
    ]  # fmt: skip


def test_interface_show_header_nested_from_another_package(ros2lab: Callable[..., Result]) -> None:
    lines = ros2lab("interface", "show", "std_msgs/msg/Header").out.splitlines()
    fields = [line for line in lines if line.strip() and not line.lstrip().startswith("#")]
    assert fields == ["builtin_interfaces/Time stamp", "\tint32 sec", "\tuint32 nanosec", "string frame_id"]


def test_interface_show_unknown_type_exits_1(ros2lab: Callable[..., Result]) -> None:
    result = ros2lab("interface", "show", "std_msgs/msg/Nope")
    assert result.code == 1
    assert "std_msgs/msg/Nope" in result.err
