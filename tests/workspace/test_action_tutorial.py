"""ROS 2's action tutorial as two processes started with ``ros2lab run`` against a live lab: the
Fibonacci server and client print what rclpy prints; a goal is cancelled, one is rejected by the
goal callback; ``ros2lab action`` lists, describes and sends goals to the server process; a plain
Zenoh session finds the action on the wire and sends it a goal as rmw_zenoh would."""

from __future__ import annotations

import json
import os
import re
import struct
import subprocess
import threading
import time
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest
import zenoh
from processes.node_process import NodeProcess
from ros_reference import ROS_REFERENCE_HASHES
from rosbags.typesys import Stores, get_types_from_msg, get_typestore
from support.app import REPO, App
from support.forked_cli import cli_command

from .action_packages import PACKAGE, demos_clone
from .test_colcon_run import RUN_S, finish, ros2lab

STAMP = r"\[\d+\.\d{9}\]"
PARTS = ("send_goal", "cancel_goal", "get_result", "feedback", "status")
TOKEN = re.compile(r"/(SS|MP)/%/%/fibonacci_action_server/%fibonacci%_action%(\w+)/([^/]+)/RIHS01_(\w{64})/")
FIB_10 = "[0, 1, 1, 2, 3, 5, 8, 13, 21, 34, 55]"


@pytest.fixture(scope="module")
def lab(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[App, Path]]:
    root = tmp_path_factory.mktemp("action_tutorial")
    ws = root / "lab_ws"
    demos_clone(ws)
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
        yield app, root
    finally:
        app.stop()


class Run(NodeProcess):
    """``ros2lab run action_tutorials_py EXECUTABLE ARGS``, its output read as it comes."""

    def __init__(self, app: App, cwd: Path, executable: str, *args: str) -> None:
        self.name = executable
        self.proc = subprocess.Popen(
            cli_command("--url", app.url, "run", PACKAGE, executable, *args, unbuffered=True),
            cwd=cwd,
            env=dict(os.environ),
            text=True,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
        )
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
    code, out, err = finish(
        ros2lab(
            app,
            root,
            "action",
            "send_goal",
            "--feedback",
            "/fibonacci",
            "action_tutorials_interfaces/action/Fibonacci",
            "{order: 3}",
        )
    )
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
    app.wait_for(
        lambda: not any(s["servers"] for s in app.get("/api/services") if s["name"].startswith("/fib")),
        "the server's services gone with its process",
    )
    code, out, err = finish(ros2lab(app, root, "action", "list"))
    assert (code, out) == (0, ""), err


def test_the_action_is_on_the_wire_as_rmw_zenoh_carries_it(run: type[Run], lab: tuple[App, Path]) -> None:
    """A plain ``eclipse-zenoh`` session, with nothing of this project, finds the server's tokens
    and sends it a goal: keys, type names and hashes, the attachment and CDR written by hand."""
    app, _root = lab
    server = run("fibonacci_action_server")
    app.wait_for(
        lambda: any(s["servers"] for s in app.get("/api/services") if s["name"].startswith("/fib")),
        "the server's services in the graph",
        RUN_S,
    )
    config = zenoh.Config()
    config.insert_json5("mode", json.dumps("client"))
    config.insert_json5("connect/endpoints", json.dumps([f"tcp/{app.router}"]))
    config.insert_json5("scouting/multicast/enabled", "false")
    session = zenoh.open(config)
    try:
        found: dict[str, tuple[str, str, str]] = {}
        deadline = time.monotonic() + RUN_S
        while len(found) < len(PARTS) and time.monotonic() < deadline:  # declared one after another
            for reply in session.liveliness().get("@ros2_lv/0/**"):
                match = TOKEN.search(str(reply.ok.key_expr)) if reply.ok is not None else None
                if match:
                    found[match[2]] = (match[1], match[3], match[4])
        pkg = "action_tutorials_interfaces::action::dds_::Fibonacci"
        assert {part: kind_type for part, (*kind_type, _hash) in found.items()} == {
            "send_goal": ["SS", f"{pkg}_SendGoal_"],
            "get_result": ["SS", f"{pkg}_GetResult_"],
            "cancel_goal": ["SS", "action_msgs::srv::dds_::CancelGoal_"],
            "feedback": ["MP", f"{pkg}_FeedbackMessage_"],
            "status": ["MP", "action_msgs::msg::dds_::GoalStatusArray_"],
        }
        assert found["cancel_goal"][2] == ROS_REFERENCE_HASHES["action_msgs/srv/CancelGoal"]
        assert found["status"][2] == ROS_REFERENCE_HASHES["action_msgs/msg/GoalStatusArray"]

        store = get_typestore(Stores.EMPTY)  # the request and response as rosbags builds them from text
        store.register(get_types_from_msg("uint8[16] uuid", "unique_identifier_msgs/msg/UUID"))
        store.register(get_types_from_msg("int32 order", "p/msg/Goal"))
        store.register(
            get_types_from_msg("unique_identifier_msgs/UUID goal_id\np/Goal goal", "p/msg/Request")
        )
        store.register(get_types_from_msg("bool accepted\nbuiltin_interfaces/Time stamp", "p/msg/Response"))
        types = store.types
        request = types["p/msg/Request"](
            types["unique_identifier_msgs/msg/UUID"](np.arange(16, dtype=np.uint8)), types["p/msg/Goal"](2)
        )
        key = f"0/fibonacci/_action/send_goal/{pkg}_SendGoal_/RIHS01_{found['send_goal'][2]}"
        attachment = struct.pack("<qqB", 1, time.time_ns(), 16) + bytes(range(100, 116))
        replies = list(
            session.get(
                key,
                payload=bytes(store.serialize_cdr(request, "p/msg/Request")),
                attachment=attachment,
                timeout=RUN_S,
            )
        )
        assert len(replies) == 1 and replies[0].ok is not None, replies
        answer = store.deserialize_cdr(replies[0].ok.payload.to_bytes(), "p/msg/Response")
        assert answer.accepted and answer.stamp.sec > 0
        echoed = replies[0].ok.attachment.to_bytes()
        assert (
            struct.unpack_from("<q", echoed)[0] == 1 and echoed[16:] == attachment[16:]
        )  # matched by seq and GID
    finally:
        session.close()
    server.wait_for(rf"^\[INFO\] {STAMP} \[fibonacci_action_server\]: Feedback: array\('i', \[0, 1, 1\]\)$")
    stopped_cleanly(server)
