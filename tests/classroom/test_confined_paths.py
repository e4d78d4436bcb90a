"""On a class server, bag and launch paths are names inside the world's own folders: a student
plays their own bag and launches the class's packages, never another world's bag or a file by its
path on the server, and a refusal reads the same whether or not the path exists."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from classroom.test_classroom_api import auth, class_settings, join
from node_runtime.ament.index import HERE as BUILTIN_PACKAGES
from node_runtime.bus import ManualClock
from server.app import create_app
from server.host.settings import ClassroomSettings, LabSettings, Listening, Settings

MY_LAUNCH = """<launch>
  <node pkg="sensor_simulation" exec="pressure.py" name="my_pressure"/>
</launch>
"""


@pytest.fixture
def folders(tmp_path: Path) -> tuple[Path, Path]:
    """The bag folder, and Ada's workspace (each world has its own in the class's workspaces)."""
    workspace = tmp_path / "workspaces" / "ada"
    (workspace / "src" / "mine" / "launch").mkdir(parents=True)
    (workspace / "src" / "mine" / "launch" / "mine.launch").write_text(MY_LAUNCH)
    return tmp_path / "bags", workspace


@pytest.fixture
def client(folders: tuple[Path, Path]) -> Iterator[TestClient]:
    bags, workspace = folders
    settings = class_settings(
        bag_dir=bags, workspaces_dir=workspace.parent, world={"writes_hz": 1000.0, "writes_burst": 1000}
    )
    with TestClient(create_app(settings, ManualClock(1_000.0))) as test_client:
        yield test_client


def record_bag(client: TestClient, token: str, name: str) -> None:
    started = client.post(
        "/api/bag/recordings", headers=auth(token), json={"topics": ["/countdown"], "name": name}
    )
    assert started.status_code == 201, started.text
    stopped = client.post(f"/api/bag/recordings/{name}/stop", headers=auth(token))
    assert stopped.status_code == 200, stopped.text


def players(client: TestClient, token: str) -> int:
    world = client.get("/api/classroom/me", headers=auth(token)).json()["world"]
    return len(client.app.state.classroom.worlds[world].lab.bags.players)  # type: ignore[attr-defined]


def same_refusal(answers: dict[str, tuple[int, str]]) -> None:
    """Every answer 404, with the same text once the path it names is taken out."""
    texts = {(status, text.replace(repr(path), "<path>")) for path, (status, text) in answers.items()}
    assert len(texts) == 1, answers
    assert next(iter(texts))[0] == 404


def test_a_student_plays_their_own_bag_and_no_other_path(
    client: TestClient, folders: tuple[Path, Path]
) -> None:
    bags, _ = folders
    ada, bob = join(client, "Ada"), join(client, "Bob")
    record_bag(client, bob, "bobs")
    record_bag(client, ada, "adas")
    bobs_folder = bags / "bob" / "bobs"
    assert any(bobs_folder.glob("*.mcap"))  # what a student reached by its path before
    tried = [
        str(bobs_folder),
        str(next(bobs_folder.glob("*.mcap"))),
        "../bob/bobs",
        "bobs",
        "/etc",
        "/etc/hostname",
        "/no/such/folder",
        "../../nothing-here",
        str(bags / "bob" / "missing"),
    ]
    answers = {}
    for path in tried:
        reply = client.post("/api/bag/players", headers=auth(ada), json={"bag": path})
        answers[path] = (reply.status_code, reply.json()["detail"])
    same_refusal(answers)
    assert players(client, ada) == 0

    own = client.post("/api/bag/players", headers=auth(ada), json={"bag": "adas"})
    assert own.status_code == 201, own.text
    assert players(client, ada) == 1


def test_a_student_launches_the_class_packages_and_no_other_path(client: TestClient) -> None:
    ada = join(client, "Ada")
    builtin = BUILTIN_PACKAGES / "sensor_simulation" / "launch" / "sensors.launch"
    refused = {
        str(builtin): None,
        "/etc/hostname": None,
        "/no/such.launch": None,
        "../ada/src/mine/launch/mine.launch": None,
        "src/mine/launch/missing.launch": None,
        "../../etc/hostname": "sensor_simulation",
        "../launch/sensors.launch": "sensor_simulation",
        "missing.launch": "sensor_simulation",
    }
    answers = {}
    for path, package in refused.items():
        body = {"file": path} if package is None else {"file": path, "package": package}
        reply = client.post("/api/launch", headers=auth(ada), json=body)
        answers[path] = (reply.status_code, reply.json()["detail"])
    same_refusal(answers)
    assert client.get("/api/launches", headers=auth(ada)).json() == []

    for body in (
        {"package": "sensor_simulation", "file": "sensors.launch"},
        {"package": "mine", "file": "mine.launch"},
        {"file": "src/mine/launch/mine.launch"},
    ):
        reply = client.post("/api/launch", headers=auth(ada), json=body)
        assert reply.status_code == 201, (body, reply.text)
    assert len(client.get("/api/launches", headers=auth(ada)).json()) == 3


def test_a_single_lab_on_loopback_keeps_paths_of_its_users_files(folders: tuple[Path, Path]) -> None:
    bags, workspace = folders
    settings = Settings(
        listen=Listening(allowed_hosts=("testserver",)),
        lab=LabSettings(
            launch="rocket",
            launch_args={"start_delay": "3600"},
            viewer=False,
            bag_dir=bags,
            workspace=workspace,
        ),
    )
    assert not settings.confines_paths
    with TestClient(create_app(settings, ManualClock(1_000.0))) as lab:
        elsewhere = workspace / "src" / "mine" / "launch" / "mine.launch"
        assert lab.post("/api/launch", json={"file": str(elsewhere)}).status_code == 201
        assert (
            lab.post("/api/bag/recordings", json={"topics": ["/countdown"], "name": "b"}).status_code == 201
        )
        assert lab.post("/api/bag/recordings/b/stop").status_code == 200
        assert lab.post("/api/bag/players", json={"bag": str((bags / "b").resolve())}).status_code == 201


def test_a_lab_beyond_loopback_confines_paths_as_a_class_does() -> None:
    assert Settings(listen=Listening(host="0.0.0.0", token="t")).confines_paths
    assert Settings(classroom=ClassroomSettings()).confines_paths
    assert not Settings(listen=Listening(host="127.0.0.2")).confines_paths


INCLUDES = """<launch>
  <include file="{file}"/>
</launch>
"""
ENV_LAUNCH = """<launch>
  <node pkg="sensor_simulation" exec="pressure.py" name="$(env {variable})"/>
</launch>
"""


def write_including(workspace: Path, name: str, file: str) -> str:
    """A launch file of the student's package that includes ``file``; its path in the workspace."""
    (workspace / "src" / "mine" / "launch" / name).write_text(INCLUDES.format(file=file))
    return f"src/mine/launch/{name}"


def test_an_include_reaches_the_worlds_packages_and_no_file_elsewhere(
    client: TestClient, folders: tuple[Path, Path], tmp_path: Path
) -> None:
    _, workspace = folders
    outside = tmp_path / "outside.launch"  # a launch file on the server, outside the world's folders
    outside.write_text(MY_LAUNCH)
    secret = tmp_path / "secret.txt"  # not XML: reading it would quote its first line in the error
    secret.write_text("the first line of a file on the server\n")
    ada = join(client, "Ada")
    answers = {}
    for i, target in enumerate((outside, secret, tmp_path / "missing.launch", Path("/etc/hostname"))):
        file = write_including(workspace, f"out{i}.launch", str(target))
        reply = client.post("/api/launch", headers=auth(ada), json={"file": file})
        detail = reply.json()["detail"]
        assert "first line" not in str(detail)
        answers[str(target)] = (reply.status_code, str(detail).replace(file, "<file>"))
    texts = {(status, text.replace(path, "<path>")) for path, (status, text) in answers.items()}
    assert len(texts) == 1, answers
    status, text = next(iter(texts))
    assert 400 <= status < 500 and "included file not found" in text
    assert client.get("/api/launches", headers=auth(ada)).json() == []

    for i, target in enumerate(("$(find-pkg-share sensor_simulation)/launch/sensors.launch", "mine.launch")):
        file = write_including(workspace, f"in{i}.launch", target)
        reply = client.post("/api/launch", headers=auth(ada), json={"file": file})
        assert reply.status_code == 201, (target, reply.text)
    assert len(client.get("/api/launches", headers=auth(ada)).json()) == 2


def test_a_worlds_launch_sees_no_variable_of_the_servers_environment(
    client: TestClient, folders: tuple[Path, Path], monkeypatch: pytest.MonkeyPatch
) -> None:
    _, workspace = folders
    monkeypatch.setenv("SERVER_SECRET", "hunter2")
    launch = workspace / "src" / "mine" / "launch"
    (launch / "env.launch").write_text(ENV_LAUNCH.format(variable="SERVER_SECRET"))
    (launch / "default.launch").write_text(ENV_LAUNCH.format(variable="SERVER_SECRET from_default"))
    ada = join(client, "Ada")
    refused = client.post("/api/launch", headers=auth(ada), json={"file": "src/mine/launch/env.launch"})
    assert 400 <= refused.status_code < 500 and "SERVER_SECRET" in str(refused.json()["detail"])
    assert "hunter2" not in refused.text
    taken = client.post("/api/launch", headers=auth(ada), json={"file": "src/mine/launch/default.launch"})
    assert taken.status_code == 201, taken.text
    assert [node["name"] for node in taken.json()["nodes"]] == ["/from_default"]
    assert "hunter2" not in taken.text


def test_a_single_lab_on_loopback_includes_its_users_files_anywhere(
    folders: tuple[Path, Path], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    bags, workspace = folders
    outside = tmp_path / "outside.launch"
    outside.write_text(ENV_LAUNCH.format(variable="MY_NODE_NAME"))
    monkeypatch.setenv("MY_NODE_NAME", "named_from_env")
    settings = Settings(
        listen=Listening(allowed_hosts=("testserver",)),
        lab=LabSettings(
            launch="rocket",
            launch_args={"start_delay": "3600"},
            viewer=False,
            bag_dir=bags,
            workspace=workspace,
        ),
    )
    with TestClient(create_app(settings, ManualClock(1_000.0))) as lab:
        file = write_including(workspace, "out.launch", str(outside))
        reply = lab.post("/api/launch", json={"file": str(workspace / file)})
        assert reply.status_code == 201, reply.text
        assert [node["name"] for node in reply.json()["nodes"]] == ["/named_from_env"]
