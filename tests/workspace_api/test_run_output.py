"""Run a node written through the workspace API and read its output over
``WS /ws/launches/{id}/output``: its lines as they come, Stop (Ctrl-C, then the end after a grace)
and its exit; a fast printer's lines dropped and counted instead of held; and the limit of
running node processes per world (429 with the reason). The lab's graph is on Zenoh (a router on
a free loopback port), as node processes need."""

from __future__ import annotations

import json
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient
from starlette.testclient import WebSocketTestSession
from support.app import free_port
from support.wait import wait_until
from support.ws import receive_within

from api.errors import CloseCode
from node_runtime.transport.config import ZenohSettings

from .helpers import lab_client, lab_settings, save

PACKAGE = "simple_control"
TALKER = """import time

import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node


def main():
    rclpy.init()
    node = Node('talker')
    node.get_logger().info('talker ready')
    count = 0
    try:
        while True:
            count += 1
            print(f'tick {count}', flush=True)
            time.sleep(0.05)
    except (KeyboardInterrupt, ExternalShutdownException):
        print('stopped by Ctrl-C', flush=True)
    finally:
        rclpy.try_shutdown()
"""
FLOOD = """def main():
    for i in range(20000):
        print(f'flood line {i}')
    print('flood done', flush=True)
"""
QUICK = """import sys


def main():
    print('about to fail', flush=True)
    sys.exit(3)
"""


@pytest.fixture(scope="module")
def client(tmp_path_factory: pytest.TempPathFactory) -> Iterator[TestClient]:
    workspace = tmp_path_factory.mktemp("run") / "workspace"
    zenoh = ZenohSettings(listen=(f"tcp/127.0.0.1:{free_port()}",))
    with lab_client(lab_settings(workspace, zenoh=zenoh, limits={"max_running_nodes": 2})) as test_client:
        made = test_client.post(
            "/api/workspace/packages", json={"name": PACKAGE, "build_type": "ament_python"}
        )
        assert made.status_code == 201, made.text
        for name, text in (("talker", TALKER), ("flood", FLOOD), ("quick", QUICK)):
            assert save(test_client, f"src/{PACKAGE}/{PACKAGE}/{name}.py", text).status_code == 201
        setup = test_client.get(f"/api/workspace/files/src/{PACKAGE}/setup.py").json()
        scripts = ", ".join(f"'{n} = {PACKAGE}.{n}:main'" for n in ("talker", "flood", "quick"))
        text = setup["text"].replace(
            "'console_scripts': [\n", f"'console_scripts': [\n            {scripts},\n"
        )
        assert text != setup["text"]
        assert (
            save(test_client, f"src/{PACKAGE}/setup.py", text, **{"If-Match": setup["etag"]}).status_code
            == 200
        )
        yield test_client


def run(client: TestClient, executable: str) -> str:
    reply = client.post("/api/run", json={"package": PACKAGE, "executable": executable})
    assert reply.status_code == 201, reply.text
    node = reply.json()["nodes"][0]
    assert node["error"] is None and node["state"] == "running", node
    return str(reply.json()["id"])


START_S = 30.0  # a node process's start on a loaded 2-core machine (Zenoh, rclpy) took over 10 s


def frames_until(ws: WebSocketTestSession, done: Any, limit: int = 50_000) -> list[dict[str, Any]]:
    """Frames until ``done(frame)`` holds (bounded in count and, per frame, in time)."""
    seen: list[dict[str, Any]] = []
    for _ in range(limit):
        message = receive_within(ws, START_S)
        if message["type"] == "websocket.close":
            pytest.fail(f"closed ({message.get('code')}) before the awaited frame; last {seen[-5:]}")
        frame = json.loads(message["text"])
        seen.append(frame)
        if done(frame):
            return seen
    pytest.fail(f"no awaited frame in {limit}; last {seen[-5:]}")


def test_run_output_streams_lines_then_stop_ends_with_an_exit(client: TestClient) -> None:
    group = run(client, "talker")
    with client.websocket_connect(f"/ws/launches/{group}/output") as ws:
        first = frames_until(ws, lambda f: f["type"] == "line" and f["text"].startswith("tick 3"))
        lines = [f for f in first if f["type"] == "line"]
        assert any("talker ready" in f["text"] for f in lines)  # the node's log line, as ROS 2 prints it
        assert all(f["stream"] == "stdout" and f["node"] == lines[0]["node"] for f in lines)
        assert [f["seq"] for f in lines] == list(range(lines[0]["seq"], lines[0]["seq"] + len(lines)))
        stopped = client.delete(f"/api/launches/{group}")
        assert stopped.status_code == 200
        rest = frames_until(ws, lambda f: f["type"] == "end")
        exit_frame = next(f for f in rest if f["type"] == "exit")
        assert any(
            f.get("text") == "stopped by Ctrl-C" for f in rest
        )  # SIGINT first: the node's own handler ran
        assert exit_frame == {"type": "exit", "node": lines[0]["node"], "code": 0, "signal": None}
        closing = receive_within(ws)
        assert closing["type"] == "websocket.close" and closing["code"] == 1000


def test_run_output_says_when_the_process_started_and_when_its_node_joined(client: TestClient) -> None:
    group = run(client, "talker")
    try:
        with client.websocket_connect(f"/ws/launches/{group}/output") as ws:
            frames = frames_until(ws, lambda f: f["type"] == "joined")
        kinds = [f["type"] for f in frames]
        assert kinds.count("started") == 1 and kinds.index("started") < kinds.index("joined")
        started, joined = frames[kinds.index("started")], frames[-1]
        assert joined == {"type": "joined", "node": started["node"], "names": ["/talker"]}
        # The pid is the process's: the graph places the node there.
        nodes = {n["name"]: n for n in client.get("/api/nodes").json()}
        assert nodes["/talker"]["location"] == f"process {started['pid']}"
    finally:
        assert client.delete(f"/api/launches/{group}").status_code == 200


def test_run_output_a_process_with_no_node_starts_and_never_joins(client: TestClient) -> None:
    group = run(client, "quick")  # prints and exits: no rclpy, no node in the graph
    with client.websocket_connect(f"/ws/launches/{group}/output") as ws:
        frames = frames_until(ws, lambda f: f["type"] == "end")  # the end is the marker: nothing after
    kinds = [f["type"] for f in frames]
    assert kinds[0] == "started" and "joined" not in kinds and kinds[-2:] == ["exit", "end"]
    assert client.delete(f"/api/launches/{group}").status_code == 200


def test_run_output_a_late_socket_gets_the_kept_lines_and_the_exit_code(client: TestClient) -> None:
    group = run(client, "quick")

    def died() -> bool:
        launches = {g["id"]: g for g in client.get("/api/launches").json()}
        return bool(launches[group]["nodes"][0]["exit_code"] == 3)

    wait_until(died, "the node to exit", START_S)  # the socket opens after the process is gone
    with client.websocket_connect(f"/ws/launches/{group}/output") as ws:
        frames = frames_until(ws, lambda f: f["type"] == "end")
    texts = [f["text"] for f in frames if f["type"] == "line"]
    assert "about to fail" in texts
    assert next(f for f in frames if f["type"] == "exit")["code"] == 3
    assert client.delete(f"/api/launches/{group}").status_code == 200


def test_run_output_a_fast_printer_drops_lines_and_counts_them(client: TestClient) -> None:
    group = run(client, "flood")
    with client.websocket_connect(f"/ws/launches/{group}/output") as ws:
        frames = frames_until(ws, lambda f: f["type"] == "end")
    lines = [f for f in frames if f["type"] == "line"]
    dropped = sum(f["count"] for f in frames if f["type"] == "dropped")
    assert dropped > 0 and lines[-1]["text"] == "flood done"
    assert len(lines) + dropped == lines[-1]["seq"] + 1  # every line sent or counted, none twice
    assert client.delete(f"/api/launches/{group}").status_code == 200


def test_run_leaves_no_compiled_files_in_the_workspace(
    client: TestClient, monkeypatch: pytest.MonkeyPatch
) -> None:
    # As on most machines: Python writes what it compiles beside the module it imported.
    monkeypatch.delenv("PYTHONDONTWRITEBYTECODE", raising=False)
    monkeypatch.delenv("PYTHONPYCACHEPREFIX", raising=False)
    group = run(client, "quick")  # its entry point imports simple_control.quick from the workspace

    def exited() -> bool:
        launches = {g["id"]: g for g in client.get("/api/launches").json()}
        return launches[group]["nodes"][0]["exit_code"] == 3

    wait_until(exited, "the node to exit", START_S)
    assert client.delete(f"/api/launches/{group}").status_code == 200
    paths = [entry["path"] for entry in client.get("/api/workspace/files").json()["entries"]]
    assert f"src/{PACKAGE}/{PACKAGE}/quick.py" in paths
    assert [p for p in paths if "__pycache__" in p or p.endswith(".pyc")] == []


def test_run_output_the_running_limit_is_429_with_the_reason(client: TestClient) -> None:
    groups = [run(client, "talker"), run(client, "talker")]
    try:
        refused = client.post("/api/run", json={"package": PACKAGE, "executable": "talker"})
        assert refused.status_code == 429
        assert "at most 2 running node processes in this world" in refused.json()["detail"]
        assert len(client.get("/api/launches").json()) == 2
    finally:
        for group in groups:
            assert client.delete(f"/api/launches/{group}").status_code == 200
    assert client.post("/api/run", json={"package": PACKAGE, "executable": "quick"}).status_code == 201


def test_run_output_an_unknown_launch_closes_with_4404(client: TestClient) -> None:
    with client.websocket_connect("/ws/launches/run999/output") as ws:
        message = receive_within(ws)
    assert message["type"] == "websocket.close" and message["code"] == CloseCode.NOT_FOUND


def test_run_output_the_channel_takes_no_messages(client: TestClient) -> None:
    group = run(client, "talker")
    try:
        with client.websocket_connect(f"/ws/launches/{group}/output") as ws:
            frames_until(ws, lambda f: f["type"] == "line")
            ws.send_text("hello")
            while (message := receive_within(ws, START_S))["type"] != "websocket.close":
                pass
        assert message["code"] == CloseCode.UNSUPPORTED_DATA
    finally:
        client.delete(f"/api/launches/{group}")


def test_run_output_the_default_limit_is_eight(tmp_path: Path) -> None:
    assert lab_settings(tmp_path).limits.max_running_nodes == 8
