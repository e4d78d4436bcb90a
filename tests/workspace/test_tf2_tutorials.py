"""docs.ros.org's tf2 tutorials that need no turtlesim, as the package ``learning_tf2_py`` the pages
build (tf2_packages.py), run with ``ros2lab run`` against a live lab: the static broadcaster seen
on /tf_static by ``ros2lab topic echo``, broadcasters and listeners that wait for a chain of frames
and print it, and a listener that joins after a static broadcaster."""

from __future__ import annotations

import math
import signal
import subprocess
from collections.abc import Iterator
from pathlib import Path

import pytest
from processes.node_process import NodeProcess
from support.app import REPO, App
from support.forked_cli import cli_command

from .tf2_packages import learning_tf2_py

STAMP = r"\[\d+\.\d{9}\]"
RUN_S = 60.0


@pytest.fixture(scope="module")
def lab(tmp_path_factory: pytest.TempPathFactory) -> Iterator[App]:
    root = tmp_path_factory.mktemp("tf2_tutorials")
    learning_tf2_py(root / "tf2_ws" / "src")
    app = App(
        root,
        "--launch",
        str(REPO / "server/packages/rocketship/launch/rocket.launch"),
        "--workspace",
        str(root / "tf2_ws"),
        "start_delay:=600",
        cwd=root,
    )
    try:
        yield app
    finally:
        app.stop()


@pytest.fixture
def run(lab: App, tmp_path: Path) -> Iterator[type[NodeProcess]]:
    """``ros2lab run learning_tf2_py EXECUTABLE ARGS`` as a node process whose lines a test reads."""
    started: list[NodeProcess] = []

    class Started(NodeProcess):
        def __init__(self, executable: str, *args: str) -> None:
            command = cli_command(
                "--url", lab.url, "run", "learning_tf2_py", executable, *args, unbuffered=True
            )
            super().__init__(lab, tmp_path / executable, command=command)
            started.append(self)

    yield Started
    for proc in started:
        proc.kill()


def ros2lab(lab: App, *args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        cli_command("--url", lab.url, *args),
        capture_output=True,
        text=True,
        timeout=RUN_S,
        check=False,
    )


def publishes(lab: App, topic: str, node: str) -> bool:
    """Whether the lab's graph shows ``node`` publishing on ``topic`` (the list asks nobody to listen)."""
    return any(t["name"] == topic and node in t["publishers"] for t in lab.get("/api/topics"))


def stopped_cleanly(*procs: NodeProcess) -> None:
    """Ctrl-C to all at once (each then ends by itself), and each ended as ROS 2's nodes end."""
    for proc in procs:
        proc.proc.send_signal(signal.SIGINT)
    for proc in procs:
        assert proc.finish() == 0, proc.text[-3000:]
        assert "Traceback" not in proc.text, proc.text[-3000:]


def test_static_broadcaster_is_seen_on_tf_static_by_topic_echo_started_after_it(
    lab: App, run: type[NodeProcess]
) -> None:
    broadcaster = run("static_turtle_tf2_broadcaster", "mystaticturtle", "0", "0", "1", "0", "0", "0")
    lab.wait_for(lambda: publishes(lab, "/tf_static", "/static_turtle_tf2_broadcaster"), "the broadcaster")
    echo = ros2lab(lab, "topic", "echo", "--once", "/tf_static")  # it sent its one message before this
    assert echo.returncode == 0, echo.stderr
    lines = echo.stdout.splitlines()
    assert lines[:2] == ["transforms:", "- header:"], echo.stdout
    assert "    frame_id: world" in lines and "  child_frame_id: mystaticturtle" in lines, echo.stdout
    translation = lines.index("    translation:")
    assert lines[translation + 1 : translation + 4] == ["      x: 0.0", "      y: 0.0", "      z: 1.0"]
    assert lines[translation + 5 : translation + 9] == [
        "      x: 0.0",
        "      y: 0.0",
        "      z: 0.0",
        "      w: 1.0",
    ]
    stopped_cleanly(broadcaster)


def test_listeners_wait_for_the_chain_and_print_it_once_broadcast(run: type[NodeProcess]) -> None:
    """turtle1 stands still at (1, 2) in world facing +y; carrot1 circles 10 m around it, on whole
    seconds straight ahead or behind (sin(k*pi) = 0): in world it is at x = 1 - 10 or 1 + 10, y = 2."""
    listener = run("turtle_tf2_listener")
    waiter = run("waits_for_transform")
    listener.wait_for(
        rf"^\[INFO\] {STAMP} \[turtle_tf2_frame_listener\]: Could not transform world to carrot1: "
        r'"world" passed to lookupTransform argument target_frame does not exist\. $'
    )
    waiter.wait_for(
        rf"^\[INFO\] {STAMP} \[example_waits_for_transform\]: Waiting for transform from carrot1 to world$"
    )
    turtle = run("static_turtle_tf2_broadcaster", "turtle1", "1", "2", "0", "0", "0", str(math.pi / 2))
    carrot = run("dynamic_frame_tf2_broadcaster")
    got = waiter.wait_for(
        rf"^\[INFO\] {STAMP} \[example_waits_for_transform\]: Got transform: x=(\S+) y=(\S+)$"
    )
    seen = listener.wait_for(
        rf"^\[INFO\] {STAMP} \[turtle_tf2_frame_listener\]: carrot1 in world: x=(\S+) y=(\S+) z=(\S+)$"
    )
    for x, y in [got[0].groups(), *(m.groups()[:2] for m in seen)]:
        assert min(abs(float(x) + 9.0), abs(float(x) - 11.0)) < 0.05 and float(y) == pytest.approx(
            2.0, abs=0.05
        )
    stopped_cleanly(listener, waiter, carrot, turtle)


def test_a_listener_started_after_a_static_broadcaster_still_gets_its_frame(
    lab: App, run: type[NodeProcess]
) -> None:
    broadcaster = run("static_turtle_tf2_broadcaster", "mast", "0.5", "0", "3", "0", "0", "0")
    lab.wait_for(lambda: publishes(lab, "/tf_static", "/static_turtle_tf2_broadcaster"), "the broadcaster")
    listener = run("turtle_tf2_listener", "--ros-args", "-p", "target_frame:=mast")
    listener.wait_for(
        rf"^\[INFO\] {STAMP} \[turtle_tf2_frame_listener\]: mast in world: x=0\.500 y=0\.000 z=3\.000$"
    )
    assert "Could not transform" not in listener.text  # the frame was there at its first look
    stopped_cleanly(listener, broadcaster)
