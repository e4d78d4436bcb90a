"""On a class server each world has its own workspace in the class's ``workspaces_dir``: a student
reads and writes only their own; the instructor reads any (read-only) and downloads all in one
zip; a world's workspace stays across a reset and a restart of the server, and goes when the
instructor removes the student."""

from __future__ import annotations

import json
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from classroom.test_classroom_api import CODE, auth, class_settings, join
from fastapi.testclient import TestClient
from support.app import free_port
from support.sandbox import require_sandbox
from support.wait import wait_until
from support.ws import receive_within

from api.errors import CloseCode
from node_runtime.bus import ManualClock
from node_runtime.transport.config import ZenohSettings
from server.app import create_app
from server.host.processes.start_pacing import MachineStartPacer, machine_slots_file
from server.host.settings import Settings

from .helpers import FILES, names_in

ROOM = {"writes_hz": 1000.0, "writes_burst": 1000}


def settings_in(folder: Path) -> Settings:
    return class_settings(workspaces_dir=folder, world=ROOM)


@pytest.fixture(scope="module")
def folder(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return tmp_path_factory.mktemp("class") / "workspaces"


@pytest.fixture(scope="module")
def client(folder: Path) -> Iterator[TestClient]:
    with TestClient(create_app(settings_in(folder), ManualClock(1_000.0))) as test_client:
        yield test_client


@pytest.fixture(scope="module")
def students(client: TestClient) -> dict[str, str]:
    tokens = {"ada": join(client, "Ada"), "bob": join(client, "Bob")}
    for world, token in tokens.items():
        reply = client.put(
            f"{FILES}/src/{world}_pkg/{world}.py", json={"text": f"# {world}'s\n"}, headers=auth(token)
        )
        assert reply.status_code == 201, reply.text
    return tokens


def teacher(client: TestClient) -> dict[str, str]:
    return auth(client.app.state.classroom.instructor_token)  # type: ignore[attr-defined]


def paths(client: TestClient, headers: dict[str, str], route: str = FILES) -> list[str]:
    reply = client.get(route, headers=headers)
    assert reply.status_code == 200, reply.text
    return [e["path"] for e in reply.json()["entries"] if e["kind"] == "file"]


def test_class_each_student_sees_only_their_own_files(
    client: TestClient, students: dict[str, str], folder: Path
) -> None:
    assert paths(client, auth(students["ada"])) == ["src/ada_pkg/ada.py"]
    assert paths(client, auth(students["bob"])) == ["src/bob_pkg/bob.py"]
    assert (folder / "ada" / "src/ada_pkg/ada.py").read_text() == "# ada's\n"
    assert client.get(f"{FILES}/src/bob_pkg/bob.py", headers=auth(students["ada"])).status_code == 404
    other = client.get(f"{FILES}/src/bob_pkg/bob.py", headers=auth(students["ada"], world="bob"))
    assert other.status_code == 403
    archive = client.get("/api/workspace/archive", headers=auth(students["ada"]))
    assert names_in(archive.content) == ["src/ada_pkg/ada.py"]
    assert client.get(FILES).status_code == 401  # no token


def test_class_the_instructor_reads_any_workspace(client: TestClient, students: dict[str, str]) -> None:
    route = "/api/classroom/worlds/bob/workspace/files"
    assert paths(client, teacher(client), route) == ["src/bob_pkg/bob.py"]
    read = client.get(f"{route}/src/bob_pkg/bob.py", headers=teacher(client))
    assert read.status_code == 200 and read.json()["text"] == "# bob's\n"
    assert read.headers["etag"].strip('"') == read.json()["etag"]
    assert client.get(f"{route}/src/bob_pkg/none.py", headers=teacher(client)).status_code == 404
    assert (
        client.get("/api/classroom/worlds/nobody/workspace/files", headers=teacher(client)).status_code == 404
    )
    assert (
        client.put(f"{route}/src/bob_pkg/bob.py", json={"text": "x"}, headers=teacher(client)).status_code
        == 405
    )
    assert client.get(route, headers=auth(students["ada"])).status_code == 403  # a student may not
    assert client.get(f"{route}/src/bob_pkg/bob.py", headers=auth(students["bob"])).status_code == 403


def test_class_the_instructors_zip_holds_every_workspace(
    client: TestClient, students: dict[str, str]
) -> None:
    reply = client.get("/api/classroom/workspaces/archive", headers=teacher(client))
    assert reply.status_code == 200 and reply.headers["content-type"] == "application/zip"
    assert names_in(reply.content) == ["ada/src/ada_pkg/ada.py", "bob/src/bob_pkg/bob.py"]
    assert client.get("/api/classroom/workspaces/archive", headers=auth(students["ada"])).status_code == 403


def test_class_a_reset_keeps_the_workspace(client: TestClient, students: dict[str, str]) -> None:
    assert client.post("/api/classroom/worlds/ada/reset", headers=teacher(client)).status_code == 200
    assert paths(client, auth(students["ada"])) == ["src/ada_pkg/ada.py"]


def test_class_removing_a_student_removes_their_workspace_only(
    client: TestClient, students: dict[str, str], folder: Path
) -> None:
    token = join(client, "Cleo")
    assert client.put(f"{FILES}/src/c/c.py", json={"text": "c\n"}, headers=auth(token)).status_code == 201
    assert (folder / "cleo" / "src/c/c.py").exists()
    bogus = client.delete("/api/classroom/worlds/cleo?workspace=keep", headers=teacher(client))
    assert bogus.status_code == 422 and (folder / "cleo" / "src/c/c.py").exists()  # only "remove" is a value
    # The class server always removes it; a world worker is told to with ?workspace=remove.
    assert (
        client.delete("/api/classroom/worlds/cleo?workspace=remove", headers=teacher(client)).status_code
        == 200
    )
    assert not (folder / "cleo").exists()
    assert (folder / "ada" / "src/ada_pkg/ada.py").exists()
    gus = join(client, "Gus")
    assert client.put(f"{FILES}/src/g/g.py", json={"text": "g\n"}, headers=auth(gus)).status_code == 201
    assert client.delete("/api/classroom/worlds/gus", headers=teacher(client)).status_code == 200
    assert not (folder / "gus").exists()


def test_class_a_workspace_outlives_a_restart_of_the_server_for_its_student_alone(tmp_path: Path) -> None:
    """Dana's code is hers after the restart: another "Dana" is refused (409), Dana from her
    browser (the old token in her cookie) gets it back."""
    folder = tmp_path / "workspaces"
    with TestClient(create_app(settings_in(folder), ManualClock(1_000.0))) as first:
        old = join(first, "Dana")
        assert first.put(f"{FILES}/src/d/d.py", json={"text": "d\n"}, headers=auth(old)).status_code == 201
    with TestClient(create_app(settings_in(folder), ManualClock(1_000.0))) as second:
        other = second.post("/api/classroom/join", json={"name": "Dana", "code": CODE})
        assert other.status_code == 409 and "progress or code" in other.json()["detail"], other.text
        second.cookies.set("lab_token", old)
        token = join(second, "Dana")
        assert second.get(f"{FILES}/src/d/d.py", headers=auth(token)).json()["text"] == "d\n"


SLEEPER = "import time\n\n\ndef main():\n    print('asleep', flush=True)\n    time.sleep(3600)\n"


def test_class_the_servers_limit_of_running_nodes_is_429_across_worlds(tmp_path: Path) -> None:
    zenoh = ZenohSettings(listen=(f"tcp/127.0.0.1:{free_port()}",))
    settings = class_settings(workspaces_dir=tmp_path, world=ROOM, zenoh=zenoh)
    settings = settings.model_copy(
        update={"limits": settings.limits.model_copy(update={"max_server_nodes": 1})}
    )
    with TestClient(create_app(settings)) as client:
        tokens = [join(client, "Eve"), join(client, "Finn")]
        for token in tokens:
            made = client.post(
                "/api/workspace/packages",
                headers=auth(token),
                json={"name": "sleepy", "build_type": "ament_python", "node_name": "sleeper"},
            )
            assert made.status_code == 201, made.text
            saved = client.put(
                f"{FILES}/src/sleepy/sleepy/sleeper.py", json={"text": SLEEPER}, headers=auth(token)
            )
            assert saved.status_code == 200, saved.text
        body = {"package": "sleepy", "executable": "sleeper"}
        first = client.post("/api/run", json=body, headers=auth(tokens[0]))
        assert first.status_code == 201 and first.json()["nodes"][0]["state"] == "running", first.text
        refused = client.post("/api/run", json=body, headers=auth(tokens[1]))
        assert refused.status_code == 429
        assert "at most 1 running node processes on this server" in refused.json()["detail"]
        assert (
            client.delete(f"/api/launches/{first.json()['id']}", headers=auth(tokens[0])).status_code == 200
        )

        def finn_runs() -> bool:
            reply = client.post("/api/run", json=body, headers=auth(tokens[1]))
            return reply.status_code == 201  # once Eve's node has ended, Finn has room

        wait_until(finn_runs, "room for Finn's node once Eve's ended", 30.0, poll_s=0.2)


HELLO = "def main():\n    print('only ada sees this', flush=True)\n"


def test_class_a_students_run_and_its_output_are_theirs_alone(tmp_path: Path) -> None:
    require_sandbox()  # a class server runs students' nodes in its sandbox
    zenoh = ZenohSettings(listen=(f"tcp/127.0.0.1:{free_port()}",))
    with TestClient(create_app(class_settings(workspaces_dir=tmp_path, world=ROOM, zenoh=zenoh))) as client:
        ada, bob = join(client, "Ada"), join(client, "Bob")
        made = client.post(
            "/api/workspace/packages",
            headers=auth(ada),
            json={"name": "hello", "build_type": "ament_python", "node_name": "hello"},
        )
        assert made.status_code == 201, made.text
        saved = client.put(f"{FILES}/src/hello/hello/hello.py", json={"text": HELLO}, headers=auth(ada))
        assert saved.status_code == 200, saved.text
        started = client.post("/api/run", json={"package": "hello", "executable": "hello"}, headers=auth(ada))
        assert started.status_code == 201, started.text
        group = started.json()["id"]
        # Bob's world has no such run: he neither lists it, stops it, nor reads its output.
        assert group not in [g["id"] for g in client.get("/api/launches", headers=auth(bob)).json()]
        assert group in [g["id"] for g in client.get("/api/launches", headers=auth(ada)).json()]
        assert client.delete(f"/api/launches/{group}", headers=auth(bob)).status_code == 404
        with client.websocket_connect(f"/ws/launches/{group}/output", headers=auth(bob)) as ws:
            refused = receive_within(ws)
        assert refused["type"] == "websocket.close" and refused["code"] == CloseCode.NOT_FOUND
        # Ada, whose run it is, reads its line and its exit.
        with client.websocket_connect(f"/ws/launches/{group}/output", headers=auth(ada)) as ws:
            frames: list[dict[str, Any]] = []
            while not frames or frames[-1]["type"] != "end":
                message = receive_within(ws)
                assert message["type"] == "websocket.send", (message, frames[-5:])
                frames.append(json.loads(message["text"]))
        assert "only ada sees this" in [f["text"] for f in frames if f["type"] == "line"]
        assert next(f for f in frames if f["type"] == "exit")["code"] == 0


def test_class_students_runs_at_once_start_at_their_turns_and_the_page_is_told(tmp_path: Path) -> None:
    """The class's node starts share one pacer (server/host/processes/start_pacing.py), set here to one
    start a second as on a 2-core server: of two students' Runs at once, the second, in another
    world, waits with no pid (its output says so) and then starts and prints; meanwhile a
    ``ros2lab run`` asking to start is told to come back (429), as the pacer is the same."""
    require_sandbox()
    zenoh = ZenohSettings(listen=(f"tcp/127.0.0.1:{free_port()}",))
    with TestClient(create_app(class_settings(workspaces_dir=tmp_path, world=ROOM, zenoh=zenoh))) as client:
        tokens = {name: join(client, name.title()) for name in ("ada", "bob")}
        for name, token in tokens.items():
            made = client.post(
                "/api/workspace/packages",
                headers=auth(token),
                json={"name": "hi", "build_type": "ament_python", "node_name": "hi"},
            )
            assert made.status_code == 201, made.text
            text = f"def main():\n    print('{name} started', flush=True)\n"
            saved = client.put(f"{FILES}/src/hi/hi/hi.py", json={"text": text}, headers=auth(token))
            assert saved.status_code == 200, saved.text
        pacer = client.app.state.classroom.labs.start_pacer  # type: ignore[attr-defined]
        pacer.slots, pacer.hold_s = 1, 1.0

        runs = {
            name: client.post("/api/run", json={"package": "hi", "executable": "hi"}, headers=auth(token))
            for name, token in tokens.items()
        }
        assert [r.status_code for r in runs.values()] == [201, 201], [r.text for r in runs.values()]
        ada, bob = (r.json()["nodes"][0] for r in runs.values())
        assert ada["state"] == "running" and bob["state"] == "waiting", (ada, bob)
        asked = client.get("/api/zenoh/join", params={"start": "true"}, headers=auth(tokens["ada"]))
        assert asked.status_code == 429 and int(asked.headers["Retry-After"]) >= 1, asked.text
        assert client.get("/api/zenoh/join", headers=auth(tokens["ada"])).status_code == 200  # not a start

        group = runs["bob"].json()["id"]
        with client.websocket_connect(f"/ws/launches/{group}/output", headers=auth(tokens["bob"])) as ws:
            frames: list[dict[str, Any]] = []
            while not frames or frames[-1]["type"] != "end":
                message = receive_within(ws, 30.0)
                assert message["type"] == "websocket.send", (message, frames[-5:])
                frames.append(json.loads(message["text"]))
        kinds = [f["type"] for f in frames]
        assert kinds[0] == "waiting" and frames[0]["node"] == bob["process"], frames
        assert "bob started" in [f["text"] for f in frames if f["type"] == "line"]
        assert next(f for f in frames if f["type"] == "exit")["code"] == 0
        assert pacer.admitted >= 2 and pacer.deferred >= 2  # Bob's start and the join were deferred
        # The class server's slots are the machine's: kept in its state folder, where the world
        # workers it starts on this machine take their turns too.
        assert isinstance(pacer, MachineStartPacer) and pacer.path == machine_slots_file(Path("state"))
        assert json.loads(pacer.path.read_text())["held"]
