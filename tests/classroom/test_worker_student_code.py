"""A student's node on a world worker runs in the sandbox through the class router's Unix socket,
which the class server names when it places a world. A worker on another machine (the socket named
is not there) opens a Unix socket of its own that relays to the router's TCP endpoint, and the
node joins its world's graph through it. A worker that was not given one refuses a student's node
with 409, saying why, and starts nothing.

A class server and a world worker in this process (TestClient each), the worker joined to the
class server's router on loopback; the worker is called as the class server calls it: with its
API token to host a world, and with the credential of that world alone for the student's calls.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient
from support.app import free_port
from support.sandbox import require_sandbox
from support.wait import wait_until

from classroom.test_classroom_api import class_settings
from node_runtime.transport.config import ZenohSettings
from server.app import create_app
from server.classroom import ClassServer
from server.classroom.workers import worker_api_token, world_call_token
from server.host.settings import ClassroomSettings, LabSettings, Listening, Settings, WorkerSettings

WORKER = "wt"
NODE = "def main():\n    print('hello from a worker', flush=True)\n"
TALKER = """
import rclpy
from rclpy.node import Node
from std_msgs.msg import Int64


def main():
    rclpy.init()
    node = Node('far_talker')
    pub = node.create_publisher(Int64, '/far_chatter', 10)
    node.create_timer(0.1, lambda: pub.publish(Int64(data=5)))
    print('talking', flush=True)
    rclpy.spin(node)
"""
RUN = {"package": "hello_pkg", "executable": "hello"}


@pytest.fixture(autouse=True, scope="module")
def _a_sandbox_on_this_machine() -> None:
    require_sandbox()


@pytest.fixture(scope="module")
def classes(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[ClassServer, TestClient]]:
    folder = tmp_path_factory.mktemp("worker_code") / "workspaces"
    endpoint = f"tcp/127.0.0.1:{free_port()}"
    zenoh = ZenohSettings(listen=(endpoint,))
    with TestClient(create_app(class_settings(workspaces_dir=folder, zenoh=zenoh))) as class_client:
        server: ClassServer = class_client.app.state.classroom  # type: ignore[attr-defined]
        worker = Settings(
            listen=Listening(allowed_hosts=("testserver",)),
            lab=LabSettings(
                launch="rocket",
                launch_args={"start_delay": "3600"},
                viewer=False,
                zenoh=ZenohSettings(mode="client", listen=(), connect=(endpoint,)),
            ),
            classroom=ClassroomSettings(max_worlds=3, workspaces_dir=folder),
            worker=WorkerSettings(id=WORKER, url="http://127.0.0.1:1", class_token=server.instructor_token),
        )
        with TestClient(create_app(worker)) as worker_client:
            yield server, worker_client


def host(
    server: ClassServer, worker: TestClient, world: str, domain_id: int, socket: Path | None, node: str = NODE
) -> str:
    """Host ``world`` on the worker as the class server does; the student's credential for it."""
    login = server.graph.login(domain_id)
    assert login is not None
    body: dict[str, Any] = {
        "world": world,
        "student": world.title(),
        "domain_id": domain_id,
        "launch": "rocket",
        "launch_args": {"start_delay": "3600"},
        "zenoh_user": login.user,
        "zenoh_password": login.password,
    }
    if socket is not None:
        body["router_socket"] = str(socket)
    auth = {"Authorization": f"Bearer {worker_api_token(server.instructor_token, WORKER)}"}
    reply = worker.post("/api/classroom/host", json=body, headers=auth)
    assert reply.status_code == 201, reply.text
    token = world_call_token(server.instructor_token, WORKER, world)
    made = worker.post(
        "/api/workspace/packages",
        headers={"Authorization": f"Bearer {token}"},
        json={"name": "hello_pkg", "build_type": "ament_python", "node_name": "hello"},
    )
    assert made.status_code == 201, made.text
    saved = worker.put(
        "/api/workspace/files/src/hello_pkg/hello_pkg/hello.py",
        json={"text": node},
        headers={"Authorization": f"Bearer {token}"},
    )
    assert saved.status_code == 200, saved.text
    return token


def test_a_worker_without_the_class_routers_socket_refuses_a_students_node_with_409(
    classes: tuple[ClassServer, TestClient],
) -> None:
    server, worker = classes
    token = host(server, worker, "far", 7, None)
    refused = worker.post("/api/run", json=RUN, headers={"Authorization": f"Bearer {token}"})
    assert refused.status_code == 409, refused.text
    assert "another machine than the class server" in refused.json()["detail"]
    launches = worker.get("/api/launches", headers={"Authorization": f"Bearer {token}"})
    assert launches.status_code == 200 and launches.json() == []  # nothing started


def test_a_worker_given_the_class_routers_socket_runs_a_students_node(
    classes: tuple[ClassServer, TestClient],
) -> None:
    server, worker = classes
    socket = server.graph.process_socket()
    assert socket is not None
    token = host(server, worker, "near", 8, socket)
    headers = {"Authorization": f"Bearer {token}"}
    run = worker.post("/api/run", json=RUN, headers=headers)
    assert run.status_code == 201, run.text

    def printed() -> bool:
        reply = worker.get(f"/api/launches/{run.json()['id']}/output", headers=headers)
        return any("hello from a worker" in line for p in reply.json()["processes"] for line in p["lines"])

    wait_until(printed, "the student's node's line, from the sandbox on the worker", 60.0, poll_s=0.2)


def test_a_worker_on_another_machine_relays_a_students_node_to_the_router_over_tcp(
    classes: tuple[ClassServer, TestClient],
) -> None:
    server, worker = classes
    elsewhere = Path("/on-the-class-servers-machine/ros2lab-router-x/router.sock")  # no such socket here
    token = host(server, worker, "relayed", 9, elsewhere, TALKER)
    headers = {"Authorization": f"Bearer {token}"}
    relay = worker.app.state.classroom._relay  # type: ignore[attr-defined]
    assert relay is not None and relay.path.is_socket()  # the worker's own, not the one named
    run = worker.post("/api/run", json=RUN, headers=headers)
    assert run.status_code == 201, run.text

    def joined() -> bool:
        names = {n["name"] for n in worker.get("/api/nodes", headers=headers).json()}
        return "/far_talker" in names

    wait_until(joined, "the sandboxed node in its world's graph, through the relay", 60.0, poll_s=0.2)
    assert relay.links >= 1  # its session is a link the relay carries

    def heard() -> bool:  # its topic shows a little after the node does
        reply = worker.get("/api/topics/far_chatter", headers=headers)
        return reply.status_code == 200 and (reply.json().get("latest") or {}).get("data") == 5

    wait_until(heard, "its messages in the world", 30.0, poll_s=0.2)
    stopped = worker.delete(f"/api/launches/{run.json()['id']}", headers=headers)
    assert stopped.status_code in (200, 204), stopped.text
