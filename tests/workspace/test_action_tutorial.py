"""ROS 2's action tutorial as two processes started with ``ros2lab run`` against a live lab: the
Fibonacci server and client print what rclpy prints; a goal is cancelled, one is rejected by the
goal callback; ``ros2lab action`` lists, describes and sends goals to the server process."""

from __future__ import annotations

import os
import re
import subprocess
import sys
import threading
from collections.abc import Iterator
from pathlib import Path

import pytest
from processes.node_process import NodeProcess
from support.app import REPO, App

from .action_packages import PACKAGE, demos_clone
from .test_colcon_run import RUN_S, finish, ros2lab

STAMP = r"\[\d+\.\d{9}\]"
FIB_10 = "[0, 1, 1, 2, 3, 5, 8, 13, 21, 34, 55]"


@pytest.fixture(scope="module")
def lab(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[App, Path]]:
    root = tmp_path_factory.mktemp("action_tutorial")
    ws = root / "lab_ws"
    demos_clone(ws)
    app = App(root, "--launch", str(REPO / "server/packages/rocketship/launch/rocket.launch"),
              "--workspace", str(ws), "start_delay:=600", cwd=root)  # fmt: skip
    try:
        yield app, root
    finally:
        app.stop()


class Run(NodeProcess):
    """``ros2lab run action_tutorials_py EXECUTABLE ARGS``, its output read as it comes."""

    def __init__(self, app: App, cwd: Path, executable: str, *args: str) -> None:
        self.name = executable
        self.proc = subprocess.Popen(
            [sys.executable, "-u", "-m", "server", "--url", app.url, "run", PACKAGE, executable, *args],
            cwd=cwd, env=dict(os.environ), text=True, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
        )  # fmt: skip
        self.lines: list[str] = []
        self._changed = threading.Condition()
        self._reader = threading.Thread(target=self._pump, daemon=True)
        self._reader.start()


@pytest.fixture
def run(lab: tuple[App, Path]) -> Iterator[type[Run]]:
    app, root = lab
    started: list[Run] = []

    class Started(Run):
        def __init__(self, executable: str, *args: str) -> None:
            super().__init__(app, root, executable, *args)
            started.append(self)

    yield Started
    for proc in started:
        proc.kill()


def stopped_cleanly(proc: NodeProcess) -> None:
    assert proc.interrupt() == 0, proc.text[-3000:]
    assert "Traceback" not in proc.text, proc.text[-3000:]


def test_tutorial_server_and_client_print_feedback_and_the_result_as_rclpy(run: type[Run]) -> None:
    server = run("fibonacci_action_server")
    client = run("fibonacci_action_client")
    assert client.finish(RUN_S) == 0, client.text  # it shuts down once it has the result
    client.wait_for(rf"^\[INFO\] {STAMP} \[fibonacci_action_client\]: Goal accepted :\)$")
    feedback = client.wait_for(
        rf"^\[INFO\] {STAMP} \[fibonacci_action_client\]: Received feedback: array\('i', \[([\d, ]+)\]\)$", 9
    )
    assert [len(m[1].split(", ")) for m in feedback] == list(range(3, 12))  # each step once, in order
    client.wait_for(
        rf"^\[INFO\] {STAMP} \[fibonacci_action_client\]: Result: array\('i', {re.escape(FIB_10)}\)$"
    )
    assert "Traceback" not in client.text
    server.wait_for(rf"^\[INFO\] {STAMP} \[fibonacci_action_server\]: Executing goal...$")
    server.wait_for(rf"^\[INFO\] {STAMP} \[fibonacci_action_server\]: Feedback: array\('i', \[0, 1, 1\]\)$")
    server.wait_for(
        rf"^\[INFO\] {STAMP} \[fibonacci_action_server\]: Feedback: array\('i', {re.escape(FIB_10)}\)$"
    )
    stopped_cleanly(server)


def test_a_goal_is_cancelled_after_its_first_feedback(run: type[Run]) -> None:
    server = run("cancelable_fibonacci_server")
    client = run("canceling_client")
    assert client.finish(RUN_S) == 0, client.text
    client.wait_for(rf"^\[INFO\] {STAMP} \[canceling_client\]: Goal accepted: True$")
    client.wait_for(rf"^\[INFO\] {STAMP} \[canceling_client\]: Goal successfully canceled$")
    done = client.wait_for(
        rf"^\[INFO\] {STAMP} \[canceling_client\]: Result status 5 \(canceled: True\), (\d+) numbers$"
    )
    assert int(done[0][1]) < 41  # stopped before the 40th step
    server.wait_for(rf"^\[INFO\] {STAMP} \[cancelable_fibonacci_server\]: Received cancel request$")
    server.wait_for(rf"^\[INFO\] {STAMP} \[cancelable_fibonacci_server\]: Goal canceled$")
    stopped_cleanly(server)


def test_the_goal_callback_rejects_a_goal_and_accepts_the_next(run: type[Run]) -> None:
    server = run("cancelable_fibonacci_server")
    refused = run("fibonacci_action_client", "--ros-args", "-p", "order:=50")
    assert refused.finish(RUN_S) == 0, refused.text
    refused.wait_for(rf"^\[INFO\] {STAMP} \[fibonacci_action_client\]: Goal rejected :\($")
    assert "Received feedback" not in refused.text
    server.wait_for(rf"^\[INFO\] {STAMP} \[cancelable_fibonacci_server\]: Rejecting goal of order 50$")
    accepted = run("fibonacci_action_client", "--ros-args", "-p", "order:=4")
    assert accepted.finish(RUN_S) == 0, accepted.text
    accepted.wait_for(
        rf"^\[INFO\] {STAMP} \[fibonacci_action_client\]: Result: array\('i', \[0, 1, 1, 2, 3\]\)$"
    )
    stopped_cleanly(server)


def test_ros2lab_action_verbs_find_the_server_process_and_send_it_a_goal(
    run: type[Run], lab: tuple[App, Path]
) -> None:
    app, root = lab
    server = run("fibonacci_action_server")
    code, out, err = finish(ros2lab(app, root, "action", "send_goal", "--feedback", "/fibonacci",
                                    "action_tutorials_interfaces/action/Fibonacci", "{order: 3}"))  # fmt: skip
    assert code == 0, err
    goal_id = re.search(r"^Goal accepted with ID: ([0-9a-f]{32})$", out, re.MULTILINE)
    assert goal_id is not None, out
    assert out == (
        "Waiting for an action server to become available...\n"
        "Sending goal:\n     order: 3\n\n"
        f"Goal accepted with ID: {goal_id[1]}\n\n"
        "Feedback:\n    partial_sequence:\n- 0\n- 1\n- 1\n\n"
        "Feedback:\n    partial_sequence:\n- 0\n- 1\n- 1\n- 2\n\n"
        "Result:\n    sequence:\n- 0\n- 1\n- 1\n- 2\n\n"
        "Goal finished with status: SUCCEEDED\n"
    )
    code, out, err = finish(ros2lab(app, root, "action", "send_goal", "/fibonacci", "no_msgs/action/Nope"))
    assert (code, out) == (1, "") and "The passed action type is invalid: no_msgs/action/Nope" in err, err
    code, out, err = finish(ros2lab(app, root, "action", "list", "-t"))
    assert code == 0, err
    assert "/fibonacci [action_tutorials_interfaces/action/Fibonacci]\n" in out
    code, out, err = finish(ros2lab(app, root, "action", "info", "/fibonacci", "-t"))
    assert code == 0, err
    assert out == (
        "Action: /fibonacci\nAction clients: 0\nAction servers: 1\n"
        "    /fibonacci_action_server [action_tutorials_interfaces/action/Fibonacci]\n"
    )
    stopped_cleanly(server)
    app.wait_for(lambda: not any(s["servers"] for s in app.get("/api/services") if s["name"].startswith("/fib")),
                 "the server's services gone with its process")  # fmt: skip
    code, out, err = finish(ros2lab(app, root, "action", "list"))
    assert (code, out) == (0, ""), err
