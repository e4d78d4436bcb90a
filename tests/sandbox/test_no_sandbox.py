"""A class server that cannot build the sandbox (here: no bwrap on its PATH) says why as it starts
and refuses students' nodes with a 503 naming it, starting nothing; the lab's own nodes still run
on it, and a class server that can sandbox runs the same student's node (tests/sandbox/
test_sandbox.py). The server runs as a process of its own on loopback and is ended by its id."""

from __future__ import annotations

from collections.abc import Iterator

import pytest
from support.app import App
from support.http import HTTP

from .test_sandbox import CLASS_READY_S, CODE, World, join, world_workspace

NODE = """
def main():
    print('a student node ran')


if __name__ == '__main__':
    main()
"""
LAUNCH = """<launch>
  <node pkg="sensor_simulation" exec="pressure.py" name="first_pressure"/>
  <node pkg="mine" exec="node.py" name="mine"/>
</launch>
"""
PYTHON_LAUNCH = """from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription([Node(package='sensor_simulation', executable='pressure.py', name='py_pressure')])
"""
WORLD_LAUNCH = """<launch>
  <node pkg="sensor_simulation" exec="pressure.py" name="pressure"/>
</launch>
"""


@pytest.fixture(scope="module")
def refusing(tmp_path_factory: pytest.TempPathFactory) -> Iterator[World]:
    root = tmp_path_factory.mktemp("no_sandbox")
    (root / "world.launch").write_text(WORLD_LAUNCH)
    (root / "empty_path").mkdir()
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("PATH", str(root / "empty_path"))  # the server finds no bwrap
        app = App(
            root,
            "--classroom",
            "--class-code",
            CODE,
            "--launch",
            str(root / "world.launch"),
            "--no-foxglove",
            cwd=root,
            ready_s=CLASS_READY_S,
        )
    try:
        ada = join(app, "Ada")
        package = world_workspace(root, ada) / "src" / "mine"
        (package / "launch").mkdir(parents=True)
        (package / "node.py").write_text(NODE.lstrip())
        (package / "launch" / "mine.launch").write_text(LAUNCH)
        (package / "launch" / "mine.launch.py").write_text(PYTHON_LAUNCH)
        yield ada
    finally:
        app.stop()


def test_no_sandbox_the_server_says_why_as_it_starts(refusing: World) -> None:
    assert (
        "error: students' nodes do not run on this server: no bubblewrap (bwrap) on this machine"
        in refusing.app.log_tail(20000)
    )


def test_no_sandbox_a_students_run_is_refused_with_503_naming_why(refusing: World) -> None:
    reply = refusing.post("/api/run", {"package": "mine", "executable": "node.py"})
    assert reply.status_code == 503, reply.text
    assert "no bubblewrap (bwrap)" in reply.json()["detail"]
    assert "--student-code unsandboxed" in reply.json()["detail"]
    assert refusing.get("/api/launches").json() == []


def test_no_sandbox_a_launch_with_a_students_node_starts_nothing(refusing: World) -> None:
    before = {str(n["name"]) for n in refusing.get("/api/nodes").json()}
    reply = refusing.post("/api/launch", {"package": "mine", "file": "mine.launch"})
    assert reply.status_code == 503, reply.text
    after = {str(n["name"]) for n in refusing.get("/api/nodes").json()}
    assert "/first_pressure" not in after and after == before
    assert refusing.get("/api/launches").json() == []


def test_no_sandbox_the_labs_own_nodes_still_run(refusing: World) -> None:
    reply = refusing.post(
        "/api/run", {"package": "sensor_simulation", "executable": "pressure.py", "name": "p2"}
    )
    assert reply.status_code == 201, reply.text
    assert "/p2" in {str(n["name"]) for n in refusing.get("/api/nodes").json()}
    assert (
        HTTP.delete(
            f"{refusing.app.url}/api/launches/{reply.json()['id']}", headers=refusing.headers(), timeout=30
        ).status_code
        == 200
    )


def test_no_sandbox_a_python_launch_file_is_not_evaluated(refusing: World) -> None:
    """Its generate_launch_description() is a student's code too: refused as their nodes are."""
    reply = refusing.post("/api/launch", {"package": "mine", "file": "mine.launch.py"})
    assert reply.status_code == 503, reply.text
    assert "no bubblewrap (bwrap)" in reply.json()["detail"]
    assert "/py_pressure" not in {str(n["name"]) for n in refusing.get("/api/nodes").json()}
    assert refusing.get("/api/launches").json() == []
