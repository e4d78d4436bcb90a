"""launch.py: ``launch`` and ``run`` arguments, and both verbs against a live server."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import pytest

from server.cli.client import CliError
from server.cli.launch import launch_request

from .conftest import LiveServer, Result, Running


def test_launch_request_file_made_absolute_with_arguments(tmp_path: Path) -> None:
    body = launch_request(["my.launch", "start_delay:=2.0", "keyboard:=false"], cwd=str(tmp_path))
    assert body == {"file": str(tmp_path / "my.launch"), "args": {"start_delay": "2.0", "keyboard": "false"}}


def test_launch_request_package_and_file() -> None:
    assert launch_request(["rocketship", "rocket.launch", "a:=b:=c"]) == {
        "package": "rocketship", "file": "rocket.launch", "args": {"a": "b:=c"},
    }  # fmt: skip


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
    assert (code, err) == (0, "")
    assert "/CliCountDown" not in node_names(live_server)
    assert not [g for g in live_server.get("/api/launches") if "cli_test.launch" in g["file"]]


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
    running.read_until(lambda line: line.startswith("[INFO] [launch]: process started: /RunCountDown"))
    live_server.wait_until(
        lambda: "/run_countdown" in {t["name"] for t in live_server.get("/api/topics")}, "the remapped topic"
    )
    code, _ = running.interrupt()
    assert code == 0
    assert "/RunCountDown" not in node_names(live_server)


def test_run_unknown_executable_exits_1_with_the_servers_message(ros2lab: Callable[..., Result]) -> None:
    result = ros2lab("run", "rocketship", "no_such_exec")
    assert result.code == 1
    assert "no_such_exec" in result.err
