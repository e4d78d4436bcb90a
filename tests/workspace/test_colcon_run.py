"""Packages cloned below ``src/`` run with ``ros2lab run`` against a live lab, found as colcon finds
them; the workspace is the lab's own (asked of the lab), and bad packages are one line each."""

from __future__ import annotations

import re
import signal
import subprocess
from collections.abc import Iterator
from pathlib import Path

import pytest
from support.app import REPO, App
from support.forked_cli import cli_command

from .tutorial_packages import examples_clone, manifest, write

RUN_S = 60.0


@pytest.fixture(scope="module")
def lab(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[App, Path]]:
    root = tmp_path_factory.mktemp("colcon_run")
    ws = root / "lab_ws"
    examples_clone(ws)
    write(
        ws / "src",
        {
            "broken/package.xml": "<package format='3'>\n  <name>broken</name>\n  <oops>\n</package>\n",
            "one/twin/package.xml": manifest("twin"),
            "other/twin/package.xml": manifest("twin"),
        },
    )
    for leftover in ("build", "install", "log"):  # a real colcon's output: never in the way
        write(ws / leftover, {"examples_rclpy_executors/package.xml": manifest("examples_rclpy_executors")})
    app = App(
        root,
        "--launch",
        str(REPO / "server/packages/rocketship/launch/rocket.launch"),
        "--workspace",
        str(ws),
        "start_delay:=600",
        cwd=root,
    )
    try:
        yield app, ws
    finally:
        app.stop()


def ros2lab(app: App, cwd: Path, *args: str) -> subprocess.Popen[str]:
    return subprocess.Popen(
        cli_command("--url", app.url, *args),
        cwd=cwd,
        text=True,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )


def finish(proc: subprocess.Popen[str], timeout_s: float = RUN_S) -> tuple[int, str, str]:
    try:
        out, err = proc.communicate(timeout=timeout_s)
    except subprocess.TimeoutExpired:
        proc.kill()
        out, err = proc.communicate()
        pytest.fail(f"the command did not end within {timeout_s} s: {out[-2000:]} {err[-2000:]}")
    return proc.returncode, out, err


def test_nested_publisher_and_subscriber_talk_as_processes(lab: tuple[App, Path], tmp_path: Path) -> None:
    app, _ws = lab  # run from a folder with no ./workspace: the lab names its own
    listener = ros2lab(
        app,
        tmp_path,
        "run",
        "examples_rclpy_minimal_subscriber",
        "subscriber_member_function",
        "--ros-args",
        "-r",
        "__node:=ear",
    )
    talker = ros2lab(app, tmp_path, "run", "examples_rclpy_minimal_publisher", "publisher_member_function")
    try:
        code, out, err = finish(listener)
    finally:
        talker.send_signal(signal.SIGINT)
    talker_code, _talker_out, talker_err = finish(talker)
    assert code == 0, err
    assert "argv: --ros-args -r __node:=ear" in out
    heard = re.findall(r"^\[INFO\] \[\d+\.\d+\] \[ear\]: I heard: \"Hello World: (\d+)\"$", err, re.MULTILINE)
    assert len(heard) == 3, err
    assert talker_code == 0, talker_err
    assert re.search(
        r"^\[INFO\] \[\d+\.\d+\] \[minimal_publisher\]: Publishing: \"Hello World: 0\"$",
        talker_err,
        re.MULTILINE,
    ), talker_err


def test_composed_process_imports_its_own_packages_modules(lab: tuple[App, Path], tmp_path: Path) -> None:
    app, _ws = lab
    code, out, err = finish(ros2lab(app, tmp_path, "run", "examples_rclpy_executors", "composed"))
    assert code == 0, err
    assert len(re.findall(r"^I heard: \[Hello World: \d+\]$", out, re.MULTILINE)) >= 3, out
    assert out.rstrip().endswith("composed: done"), out


def test_pkg_verbs_list_the_labs_workspace(lab: tuple[App, Path], tmp_path: Path) -> None:
    app, ws = lab
    code, out, err = finish(ros2lab(app, tmp_path, "pkg", "executables", "examples_rclpy_executors"))
    assert code == 0, err
    assert out.splitlines() == [
        "examples_rclpy_executors composed",
        "examples_rclpy_executors listener_missing",
        "examples_rclpy_executors talker_missing_function",
    ]
    code, out, err = finish(ros2lab(app, tmp_path, "pkg", "prefix", "examples_rclpy_minimal_publisher"))
    assert (code, out) == (0, f"{ws / 'src/examples/rclpy/topics/minimal_publisher'}\n"), err
    code, out, err = finish(ros2lab(app, tmp_path, "pkg", "list"))
    names = out.splitlines()
    assert {"examples_rclpy_minimal_publisher", "examples_rclpy_executors", "rocketship"} <= set(names)
    assert names == sorted(names) and "twin" not in names and "broken" not in names
    assert code == 1  # and the two problems, one line each
    assert sorted(err.splitlines()) == sorted(
        [
            f"{ws / 'src/broken/package.xml'}:4: package.xml does not parse: mismatched tag",
            f"{ws / 'src/other/twin/package.xml'}: two packages are named 'twin': {ws / 'src/one/twin'} and "
            f"{ws / 'src/other/twin'}",
        ]
    )


@pytest.mark.parametrize(
    ("package", "executable", "line"),
    [
        (
            "examples_rclpy_executors",
            "listener_missing",
            r"executors/setup\.py:\d+: console script 'listener_missing = examples_rclpy_executors\.no_such_module:main':"
            r" no module 'examples_rclpy_executors\.no_such_module'",
        ),
        (
            "examples_rclpy_executors",
            "talker_missing_function",
            r"executors/setup\.py:\d+: console script .*: .*/talker\.py has no function 'no_such_function'",
        ),
        ("broken", "anything", r"src/broken/package\.xml:4: package\.xml does not parse: mismatched tag"),
        ("twin", "anything", r"two packages are named 'twin': .*/src/one/twin and .*/src/other/twin"),
    ],
)
def test_a_package_that_cannot_run_is_one_line_and_the_lab_runs_on(
    lab: tuple[App, Path], tmp_path: Path, package: str, executable: str, line: str
) -> None:
    app, _ws = lab
    nodes_before = {n["name"] for n in app.get("/api/nodes")}
    code, _out, err = finish(ros2lab(app, tmp_path, "run", package, executable))
    assert code != 0
    assert len(err.strip().splitlines()) == 1, err
    assert re.search(line, err), err
    assert app.get("/api/health")["status"] == "ok"
    assert {n["name"] for n in app.get("/api/nodes")} == nodes_before


def test_created_package_runs_at_once(lab: tuple[App, Path], tmp_path: Path) -> None:
    app, ws = lab
    created = ros2lab(
        app,
        tmp_path,
        "pkg",
        "create",
        "--build-type",
        "ament_python",
        "--node-name",
        "keyboard_manager",
        "simple_control",
        "--destination-directory",
        str(ws / "src"),
    )
    code, out, err = finish(created)
    assert code == 0, err
    assert f"creating {ws / 'src/simple_control/simple_control/keyboard_manager.py'}" in out
    code, out, err = finish(ros2lab(app, tmp_path, "run", "simple_control", "keyboard_manager"))
    assert (code, out) == (0, "Hi from simple_control.\n"), err


def test_colcon_is_a_one_line_hint(tmp_path: Path) -> None:
    done = subprocess.run(
        cli_command("colcon", "build", "--symlink-install"),
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=RUN_S,
        check=False,
    )
    assert done.returncode == 0
    assert (
        len(done.stdout.splitlines()) == 1 and "colcon build" in done.stdout and "not needed" in done.stdout
    )
    assert not (tmp_path / "build").exists()


def test_the_lab_starts_a_console_script_as_a_process(lab: tuple[App, Path]) -> None:
    app, _ws = lab  # as a launch file's <node pkg="examples_rclpy_executors" exec="composed"/> would
    started = app.post("/api/run", {"package": "examples_rclpy_executors", "executable": "composed"})
    assert started.status_code == 201, started.text
    group = started.json()["id"]

    def printed() -> list[str]:
        return [line for p in app.get(f"/api/launches/{group}/output")["processes"] for line in p["lines"]]

    app.wait_for(
        lambda: any(line.endswith("composed: done") for line in printed()), "the process's last line", RUN_S
    )
    lines = printed()
    assert any("I heard: [Hello World: " in line for line in lines), lines
    app.delete(f"/api/launches/{group}")
