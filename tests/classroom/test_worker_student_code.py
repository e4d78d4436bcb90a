"""A student's node on a world worker runs in the sandbox through the class router's Unix socket,
which the class server names when it places a world; a worker that was not given one (it runs on
another machine than the class server) refuses a student's node with 409, saying why, and starts
nothing.

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
from server.app import create_app
from server.classroom import ClassServer
from server.classroom.workers import worker_api_token, world_call_token
from server.settings import ClassroomSettings, LabSettings, Listening, Settings, WorkerSettings
from server.transport.config import ZenohSettings

WORKER = "wt"
NODE = "def main():\n    print('hello from a worker', flush=True)\n"
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
            classroom=ClassroomSettings(max_worlds=2, workspaces_dir=folder),
            worker=WorkerSettings(id=WORKER, url="http://127.0.0.1:1", class_token=server.instructor_token),
        )
        with TestClient(create_app(worker)) as worker_client:
            yield server, worker_client


def host(server: ClassServer, worker: TestClient, world: str, domain_id: int, socket: Path | None) -> str:
    """Host ``world`` on the worker as the class server does; the student's credential for it."""
    login = server.graph.login(domain_id)
    assert login is not None
    body: dict[str, Any] = {"world": world, "student": world.title(), "domain_id": domain_id, "launch": "rocket",
            "launch_args": {"start_delay": "3600"}, "zenoh_user": login.user, "zenoh_password": login.password}  # fmt: skip
    if socket is not None:
        body["router_socket"] = str(socket)
    auth = {"Authorization": f"Bearer {worker_api_token(server.instructor_token, WORKER)}"}
    reply = worker.post("/api/classroom/host", json=body, headers=auth)
    assert reply.status_code == 201, reply.text
    token = world_call_token(server.instructor_token, WORKER, world)
    made = worker.post("/api/workspace/packages", headers={"Authorization": f"Bearer {token}"},
                       json={"name": "hello_pkg", "build_type": "ament_python", "node_name": "hello"})  # fmt: skip
    assert made.status_code == 201, made.text
    saved = worker.put("/api/workspace/files/src/hello_pkg/hello_pkg/hello.py", json={"text": NODE},
                       headers={"Authorization": f"Bearer {token}"})  # fmt: skip
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
