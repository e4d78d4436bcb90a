"""launch.py: ``launch`` and ``run`` arguments, and both verbs against a live server."""

from __future__ import annotations

import contextlib
import copy
import io
import re
from collections.abc import Callable
from pathlib import Path

import pytest

from server.cli.client import CliError
from server.cli.launch import (
    ProcessLines,
    in_process_labels,
    launch_request,
    log_line,
    node_labels,
    report_faults,
)

from .conftest import LiveServer, Result, Running


def test_launch_request_file_made_absolute_with_arguments(tmp_path: Path) -> None:
    body = launch_request(["my.launch", "start_delay:=2.0", "keyboard:=false"], cwd=str(tmp_path))
    assert body == {"file": str(tmp_path / "my.launch"), "args": {"start_delay": "2.0", "keyboard": "false"}}


def test_launch_request_package_and_file() -> None:
    assert launch_request(["rocketship", "rocket.launch", "a:=b:=c"]) == {
        "package": "rocketship",
        "file": "rocket.launch",
        "args": {"a": "b:=c"},
    }


@pytest.mark.parametrize("tokens", [[], ["a:=1"], ["p", "f", "extra"], ["f", ":=1"]])
def test_launch_request_wrong_shape_refused(tokens: list[str]) -> None:
    with pytest.raises(CliError):
        launch_request(tokens)


# -- against the live server ------------------------------------------------------------------
def node_names(server: LiveServer) -> set[str]:
    return {n["name"] for n in server.get("/api/nodes?hidden=true")}


def test_launch_file_nodes_run_until_ctrl_c_then_stop(
    live_server: LiveServer, tmp_path: Path, start: Callable[..., Running]
) -> None:
    launch_file = tmp_path / "cli_test.launch"
    launch_file.write_text(
        '<launch>\n  <arg name="delay" default="5.0"/>\n'
        '  <node pkg="rocketship" exec="countdown" name="CliCountDown">\n'
        '    <param name="start_delay_s" value="$(var delay)"/>\n'
        '    <remap from="/countdown" to="/cli_countdown"/>\n  </node>\n</launch>\n'
    )
    launching = start("launch", str(launch_file), "delay:=0.1")
    launching.read_until(
        lambda line: line == "[INFO] [launch]: process started: /CliCountDown (rocketship countdown)"
    )
    assert "/CliCountDown" in node_names(live_server)
    code, err = launching.interrupt()
    assert (code, err) == (0, ""), err  # the whole of stderr, a traceback in full
    assert "/CliCountDown" not in node_names(live_server)
    assert not [g for g in live_server.get("/api/launches") if "cli_test.launch" in g["file"]]


def test_launch_prints_its_nodes_log_lines_from_the_first_as_ros2_launch_does(
    live_server: LiveServer, tmp_path: Path, start: Callable[..., Running]
) -> None:
    # The rocket's controller, on topics of its own so the live server's rocket is left alone. Its
    # first line is logged as it starts, before the server has even answered the launch request.
    launch_file = tmp_path / "controller.launch"
    launch_file.write_text(
        '<launch>\n  <node pkg="rocketship" exec="main_controller" name="CliController">\n'
        '    <remap from="/countdown" to="/cli_ctl_countdown"/>\n'
        '    <remap from="/cmd_vel" to="/cli_ctl_cmd_vel"/>\n'
        '    <remap from="/abort_takeoff" to="/cli_ctl_abort"/>\n  </node>\n</launch>\n'
    )
    launching = start("launch", str(launch_file))
    first = launching.read_until(lambda line: "Rocket Ready for Countdown" in line)
    assert re.fullmatch(
        r"\[main_controller-1\] \[INFO\] \[\d+\.\d{9}\] \[CliController\]: Rocket Ready for Countdown", first
    ), first
    # A line it logs later, and nothing from the server's other nodes (its own rocket counts down too).
    live_server.post(  # raises unless the server took it
        "/api/publish", {"topic": "/cli_ctl_countdown", "msg": {"data": 3}, "type": "std_msgs/msg/Int64"}
    )
    launching.read_until(lambda line: line.endswith("[CliController]: Countdown: 3s"))
    assert all(line.startswith(("[main_controller-1] ", "[INFO] [launch]")) for line in launching.seen), (
        launching.seen
    )
    code, err = launching.interrupt()
    assert (code, err) == (0, ""), err  # the whole of stderr, a traceback in full


def test_a_launched_node_that_crashes_or_dies_is_reported_once() -> None:
    started = {  # as the launch request answered
        "id": "g1",
        "nodes": [
            {"name": "/Countdown", "exec": "countdown", "state": "active", "error": None},
            {"name": "broken", "exec": "broken.py", "state": None, "error": "no such executable"},
            {
                "name": "Crasher",
                "exec": "crasher.py",
                "state": "running",
                "error": None,
                "process": "crasher.py-7",
            },
            {"name": "/Fine", "exec": "fine", "state": "active", "error": None},
        ],
    }
    labels = node_labels(started)
    # A node process goes by the server's label; the others are numbered in launch order.
    assert labels == {"Countdown": "countdown-1", "Crasher": "crasher.py-7", "Fine": "fine-3"}
    assert in_process_labels(started) == {"Countdown": "countdown-1", "Fine": "fine-3"}  # /rosout's
    later = copy.deepcopy(started)
    later["nodes"][0]["state"] = "crashed"
    later["nodes"][2].update(state="died", exit_code=1, error="died (exit code 1)")  # as the server says it
    reported: set[str] = set()
    printed = []
    for _ in range(2):  # the CLI asks every second: the second time says nothing new
        with contextlib.redirect_stdout(io.StringIO()) as out:
            report_faults(later, labels, reported)
        printed.append(out.getvalue().splitlines())
    assert printed == [
        [
            "[ERROR] [countdown-1]: node crashed (its last line says why)",
            "[ERROR] [crasher.py-7]: process has died [exit code 1]",
        ],
        [],
    ]
    line = log_line(
        "countdown-1",
        {"stamp": {"sec": 12, "nanosec": 5}, "level": 50, "name": "Countdown", "msg": "crashed: boom"},
    )
    assert line == "[countdown-1] [FATAL] [12.000000005] [Countdown]: crashed: boom"


def test_a_node_processs_new_lines_are_printed_once_and_a_gap_is_said() -> None:
    shown = ProcessLines()
    answers = [
        [{"label": "talky.py-1", "lines": ["a", "b"], "printed": 2}],
        [{"label": "talky.py-1", "lines": ["a", "b", "c"], "printed": 3}],
        # Five more, of which the server kept the last three (it keeps the last lines only).
        [{"label": "talky.py-1", "lines": ["f", "g", "h"], "printed": 8}],
        [{"label": "talky.py-1", "lines": ["f", "g", "h"], "printed": 8}],
    ]
    printed = []
    for processes in answers:
        with contextlib.redirect_stdout(io.StringIO()) as out:
            shown.show(processes)
        printed.append(out.getvalue().splitlines())
    assert printed == [
        ["[talky.py-1] a", "[talky.py-1] b"],
        ["[talky.py-1] c"],
        ["[talky.py-1] ... (2 lines not shown)", "[talky.py-1] f", "[talky.py-1] g", "[talky.py-1] h"],
        [],
    ]


def test_launch_package_file_error_is_one_line_with_file_and_line(
    tmp_path: Path, ros2lab: Callable[..., Result]
) -> None:
    bad = tmp_path / "bad.launch"
    bad.write_text('<launch>\n  <node pkg="rocketship" exec="countdown" colour="red"/>\n</launch>\n')
    result = ros2lab("launch", str(bad))
    assert result.code == 1
    assert result.out == ""
    assert len(result.err.splitlines()) == 1
    assert "bad.launch:2" in result.err


def test_run_node_with_ros_args_runs_until_ctrl_c(
    live_server: LiveServer, start: Callable[..., Running]
) -> None:
    running = start(
        "run",
        "rocketship",
        "countdown",
        "--ros-args",
        "-r",
        "__node:=RunCountDown",
        "-p",
        "start_delay_s:=0.1",
        "-r",
        "/countdown:=/run_countdown",
    )
    # A child process of this command, joined to the server's graph over Zenoh.
    live_server.wait_until(
        lambda: "/RunCountDown" in node_names(live_server), "the node in the server's graph"
    )
    live_server.wait_until(
        lambda: "/run_countdown" in {t["name"] for t in live_server.get("/api/topics")}, "the remapped topic"
    )
    node = next(n for n in live_server.get("/api/nodes") if n["name"] == "/RunCountDown")
    assert node["location"] != "app"
    code, _ = running.interrupt()
    assert code == 0
    live_server.wait_until(
        lambda: "/RunCountDown" not in node_names(live_server), "the node to leave the graph"
    )


def test_run_unknown_executable_exits_1_naming_it(ros2lab: Callable[..., Result]) -> None:
    result = ros2lab("run", "rocketship", "no_such_exec")
    assert result.code == 1
    assert "no_such_exec" in result.err and len(result.err.splitlines()) == 1


def test_run_unknown_package_exits_1_as_ros2_run_says(ros2lab: Callable[..., Result]) -> None:
    result = ros2lab("run", "no_such_pkg", "x")
    assert (result.code, result.err.strip()) == (1, "Package 'no_such_pkg' not found")
