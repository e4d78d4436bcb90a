"""The packages ROS 2's tutorials start, as node processes (``ros2lab run``) on a live lab, seen
through the CLI as the tutorials show them: demo_nodes' talker and listener, turtlesim."""

from __future__ import annotations

import re
import subprocess
from collections.abc import Iterator
from pathlib import Path

import pytest
from support.app import App
from support.forked_cli import cli_command

from .node_process import NodeProcess

STAMP = r"\[\d+\.\d{9}\]"
CLI_S = 60.0


@pytest.fixture(scope="module")
def lab(tmp_path_factory: pytest.TempPathFactory) -> Iterator[App]:
    root = tmp_path_factory.mktemp("tutorial_packages")
    (root / "nothing.launch.xml").write_text("<launch/>\n")
    app = App(root, "--launch", str(root / "nothing.launch.xml"), "--workspace", "no_workspace", cwd=root)
    try:
        yield app
    finally:
        app.stop()


@pytest.fixture
def run(lab: App, tmp_path: Path) -> Iterator[type[NodeProcess]]:
    """``ros2lab run PKG EXE`` as a student types it; each is ended by its own id after the test."""
    started: list[NodeProcess] = []

    class Started(NodeProcess):
        def __init__(self, package: str, executable: str) -> None:
            command = cli_command("--url", lab.url, "run", package, executable)
            super().__init__(lab, tmp_path / executable, command=command)
            started.append(self)

    yield Started
    for proc in started:
        proc.kill()


def ros2lab(lab: App, *args: str) -> tuple[int, str, str]:
    done = subprocess.run(
        cli_command("--url", lab.url, *args),
        capture_output=True,
        text=True,
        timeout=CLI_S,
        check=False,
    )
    return done.returncode, done.stdout, done.stderr


def test_demo_listener_hears_the_talker(run: type[NodeProcess]) -> None:
    listener = run("demo_nodes_cpp", "listener")
    talker = run("demo_nodes_py", "talker")
    heard = listener.wait_for(rf"^\[INFO\] {STAMP} \[listener\]: I heard: \[Hello World: (\d+)\]$", 2)
    first, second = (int(m[1]) for m in heard)
    assert second == first + 1
    talker.wait_for(rf'^\[INFO\] {STAMP} \[talker\]: Publishing: "Hello World: {first}"$')
    assert talker.interrupt() == 0 and listener.interrupt() == 0, talker.text + listener.text


def test_turtlesim_teleport_then_pose_spawn_and_background(lab: App, run: type[NodeProcess]) -> None:
    sim = run("turtlesim", "turtlesim_node")
    sim.wait_for(
        r"\[turtlesim\]: Spawning turtle \[turtle1\] at x=\[5\.544445\], y=\[5\.544445\], theta=\[0\.0+\]$"
    )
    code, out, err = ros2lab(
        lab,
        "service",
        "call",
        "/turtle1/teleport_absolute",
        "turtlesim/srv/TeleportAbsolute",
        "{x: 2.0, y: 3.0, theta: 1.5}",
    )
    assert code == 0 and "response:\nturtlesim.srv.TeleportAbsolute_Response()" in out, out + err
    code, out, err = ros2lab(lab, "topic", "echo", "--once", "/turtle1/pose")
    assert code == 0, err
    assert out.startswith("x: 2.0\ny: 3.0\ntheta: 1.5\nlinear_velocity: 0.0\nangular_velocity: 0.0\n"), out

    code, out, err = ros2lab(
        lab, "service", "call", "/spawn", "turtlesim/srv/Spawn", "{x: 2, y: 2, theta: 0.2}"
    )
    assert code == 0 and "turtlesim.srv.Spawn_Response(name='turtle2')" in out, out + err
    sim.wait_for(
        r"\[turtlesim\]: Spawning turtle \[turtle2\] at x=\[2\.000000\], y=\[2\.000000\], theta=\[0\.200000\]$"
    )
    code, out, err = ros2lab(lab, "topic", "list", "-t")
    assert code == 0, err
    assert {
        "/turtle2/pose [turtlesim/msg/Pose]",
        "/turtle2/cmd_vel [geometry_msgs/msg/Twist]",
        "/turtle1/color_sensor [turtlesim/msg/Color]",
    } <= set(out.splitlines())

    assert ros2lab(lab, "param", "get", "/turtlesim", "background_r")[1] == "Integer value is: 69\n"
    code, out, err = ros2lab(lab, "param", "set", "/turtlesim", "background_r", "150")
    assert (code, out) == (0, "Set parameter successful\n"), err
    assert ros2lab(lab, "param", "get", "/turtlesim", "background_r")[1] == "Integer value is: 150\n"
    code, out, err = ros2lab(lab, "param", "set", "/turtlesim", "background_r", "300")
    assert "Parameter background_r out of range. Min: 0, Max: 255, value: 300" in err, out + err
    assert ros2lab(lab, "param", "get", "/turtlesim", "background_r")[1] == "Integer value is: 150\n"

    code, out, err = ros2lab(lab, "action", "list", "-t")
    assert "/turtle1/rotate_absolute [turtlesim/action/RotateAbsolute]" in out.splitlines(), out + err
    code, out, err = ros2lab(
        lab,
        "action",
        "send_goal",
        "/turtle1/rotate_absolute",
        "turtlesim/action/RotateAbsolute",
        "{theta: -1.5}",
        "--feedback",
    )
    assert code == 0, out + err
    assert "Feedback:\n    remaining: -3.0" in out and out.rstrip().endswith(
        "Goal finished with status: SUCCEEDED"
    )
    assert re.search(r"Result:\n    delta: 2\.9\d+", out), out
    sim.wait_for(r"\[turtlesim\]: Rotation goal completed successfully$")
    assert sim.interrupt() == 0, sim.text
