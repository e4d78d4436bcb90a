"""``ros2lab run`` and plain ``python FILE``: a student's node as a process of their own command,
Ctrl-C through the handout's own except clause, and bad files refused in one line."""

from __future__ import annotations

import os
import re
import select
import signal
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest
from support.app import REPO, App
from support.forked_cli import cli_command

from .conftest import make_workspace, node_entry

SYNTAX_ERROR = """
import rclpy

def main(:
    pass
"""
MISSING_IMPORT = """
import rclpy
from rclpy.node import Node
import no_such_module_for_this_lab

if __name__ == '__main__':
    rclpy.init()
"""
CTRL_C_TWICE = """
import rclpy
from rclpy.node import Node


def main():
    rclpy.init()
    node = Node('CtrlCTwice')
    for which in ('first', 'second'):
        try:
            rclpy.spin(node)
        except KeyboardInterrupt:
            print(which, 'Ctrl-C', flush=True)
    rclpy.shutdown()
"""
DOES_NOTHING = """
import rclpy
from rclpy.node import Node


class Idle(Node):
    def __init__(self):
        super().__init__('Idle')
"""


@pytest.fixture(scope="module")
def lab(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[App, Path]]:
    root = tmp_path_factory.mktemp("run_cli")
    make_workspace(
        root,
        {
            "src/bad/syntax_error.py": SYNTAX_ERROR,
            "src/bad/missing_import.py": MISSING_IMPORT,
            "src/bad/does_nothing.py": DOES_NOTHING,
            "src/bad/ctrl_c_twice.py": CTRL_C_TWICE,
        },
    )
    # The rocket launch from the lab's package, with the lab's own keyboard manager (the student's
    # is started here, by ros2lab run).
    app = App(
        root,
        "--launch",
        str(REPO / "server/packages/rocketship/launch/rocket.launch"),
        "--workspace",
        "no_workspace",
        "start_delay:=600",
        cwd=root,
    )
    try:
        yield app, root
    finally:
        app.stop()


@pytest.fixture(autouse=True)
def no_student_node_left(lab: tuple[App, Path]) -> None:
    """Each test starts once the graph has forgotten the earlier tests' nodes: a stale entry would
    send a test's Ctrl-C to a process that has not started its interpreter yet."""
    app, _root = lab
    app.wait_for(lambda: node_entry(app, "/KeyboardManagerNode") is None, "the earlier nodes to leave")


def ros2lab(app: App, cwd: Path, *args: str) -> subprocess.Popen[str]:
    return subprocess.Popen(
        cli_command("--url", app.url, "run", *args),
        cwd=cwd,
        text=True,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )


def finish(proc: subprocess.Popen[str], timeout_s: float = 30.0) -> tuple[int, str, str]:
    try:
        out, err = proc.communicate(timeout=timeout_s)
    except subprocess.TimeoutExpired:
        proc.kill()
        out, err = proc.communicate()
        pytest.fail(f"the command did not end within {timeout_s} s: {err[-2000:]}")
    return proc.returncode, out, err


def test_ctrl_c_on_ros2lab_run_ends_the_node_through_its_except_clause(lab: tuple[App, Path]) -> None:
    app, root = lab
    run = ros2lab(app, root, "rocketship", "keyboard_manager.py")
    try:
        app.wait_for(
            lambda: node_entry(app, "/KeyboardManagerNode") is not None, "the node in the app's graph"
        )
    finally:
        run.send_signal(signal.SIGINT)
        code, _out, err = finish(run)
    assert code == 0, err
    assert "Traceback" not in err
    app.wait_for(lambda: node_entry(app, "/KeyboardManagerNode") is None, "the node to leave the graph", 5.0)


def test_each_ctrl_c_reaches_the_node_and_a_second_ends_one_that_caught_the_first(
    lab: tuple[App, Path],
) -> None:
    """As each Ctrl-C in a terminal reaches a node ``ros2 run`` started: the node caught the first
    and spun on; the second ended it by itself (a kill at the grace's end would be exit -9)."""
    app, root = lab
    run = ros2lab(app, root, "bad", "ctrl_c_twice.py")
    try:
        app.wait_for(lambda: node_entry(app, "/CtrlCTwice") is not None, "the node in the app's graph")
        run.send_signal(signal.SIGINT)
        assert run.stdout is not None
        ready, _, _ = select.select([run.stdout], [], [], 20.0)
        assert ready, "the node said nothing of the first Ctrl-C"
        assert run.stdout.readline() == "first Ctrl-C\n"
        assert run.poll() is None and node_entry(app, "/CtrlCTwice") is not None  # it spins on
        run.send_signal(signal.SIGINT)
    except BaseException:
        run.kill()  # the node dies with its command
        run.communicate()
        raise
    code, out, err = finish(run)
    assert code == 0, err
    assert out == "second Ctrl-C\n", out


@pytest.mark.parametrize(
    ("executable", "line"),
    [
        ("syntax_error.py", r"syntax_error\.py:3: SyntaxError"),
        (
            "missing_import.py",
            r"missing_import\.py:3: ModuleNotFoundError: No module named 'no_such_module_for_this_lab'",
        ),
        ("does_nothing.py", r"does_nothing\.py: nothing would run: it has no main\(\)"),
    ],
)
def test_a_file_that_cannot_run_is_one_line_naming_it_and_a_non_zero_exit(
    lab: tuple[App, Path], executable: str, line: str
) -> None:
    app, root = lab
    nodes_before = {n["name"] for n in app.get("/api/nodes")}
    code, _out, err = finish(ros2lab(app, root, "bad", executable))
    assert code != 0
    assert len(err.strip().splitlines()) == 1, err
    assert re.search(line, err), err
    assert app.get("/api/health")["status"] == "ok"
    assert {n["name"] for n in app.get("/api/nodes")} == nodes_before


def test_a_second_node_of_the_same_name_is_warned_about(lab: tuple[App, Path]) -> None:
    app, root = lab
    first = ros2lab(app, root, "rocketship", "keyboard_manager.py")
    second = None
    try:
        app.wait_for(lambda: node_entry(app, "/KeyboardManagerNode") is not None, "the first node")
        second = ros2lab(app, root, "rocketship", "keyboard_manager.py")
        app.wait_for(
            lambda: len([n for n in app.get("/api/nodes") if n["name"] == "/KeyboardManagerNode"]) == 2,
            "both nodes in the graph",
        )
    finally:
        for proc in (first, second):
            if proc is not None:
                proc.send_signal(signal.SIGINT)
    _code, _out, second_err = finish(second) if second is not None else (0, "", "")
    _code, _out, first_err = finish(first)
    # The newcomer when it starts, and the one already there when the newcomer appears.
    assert "a node named /KeyboardManagerNode already exists in the graph" in second_err + first_err


def test_python_file_runs_the_node_from_the_projects_environment(lab: tuple[App, Path]) -> None:
    app, root = lab
    file = root / "workspace" / "src" / "rocketship" / "src" / "keyboard_manager.py"
    zid = "1f" + os.urandom(15).hex()
    env = {**os.environ, "ZENOH_CONFIG_OVERRIDE": f'connect/endpoints=["tcp/{app.router}"];id="{zid}"'}
    proc = subprocess.Popen(
        [sys.executable, str(file)],
        cwd=root,
        env=env,
        text=True,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )
    try:
        app.wait_for(  # this process's node, by its Zenoh session id
            lambda: (node_entry(app, "/KeyboardManagerNode") or {}).get("location") == f"zenoh:{zid[:8]}",
            "python FILE's node in the graph",
        )
    finally:
        proc.send_signal(signal.SIGINT)
        code, _out, err = finish(proc)
    assert code == 0, err


def test_a_sourced_ros_2_rclpy_is_never_shadowed(tmp_path: Path) -> None:
    real = tmp_path / "ros" / "rclpy"
    real.mkdir(parents=True)
    (real / "__init__.py").write_text("FROM_ROS_2 = True\n")
    env = {**os.environ, "PYTHONPATH": str(tmp_path / "ros")}
    done = subprocess.run(
        [sys.executable, "-c", "import rclpy; print(getattr(rclpy, 'FROM_ROS_2', False))"],
        env=env,
        capture_output=True,
        text=True,
        timeout=30,
        check=True,
    )
    assert done.stdout.strip() == "True"
