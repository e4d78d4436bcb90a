"""Students' nodes on a live class server run sandboxed: each thing the sandbox blocks is tried by a
student's node run through ``POST /api/run`` on a class server that sandboxes (the default) and
on one started with ``--student-code unsandboxed``, where it must work, so no test passes by
accident. Both servers run as processes of their own on loopback, shared by the module, and are
ended by their ids."""

from __future__ import annotations

import os
import shutil
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import httpx
import pytest
from support.app import REPO, App
from support.http import HTTP
from support.sandbox import require_sandbox
from support.wait import wait_until

from server.settings import SandboxSettings


@pytest.fixture(autouse=True, scope="module")
def _a_sandbox_on_this_machine() -> None:
    require_sandbox()


CODE = "SBX042"
SECRET_ENV = "ROS2LAB_SERVER_SECRET"
HERE = Path(__file__).parent
EXAMPLES = REPO / "examples" / "workspace"
WORLD_LAUNCH = """<launch>
  <node pkg="sensor_simulation" exec="pressure.py" name="pressure"/>
</launch>
"""
TALKER = """
import rclpy
from rclpy.node import Node
from std_msgs.msg import Int64


class Talker(Node):
    def __init__(self):
        super().__init__('sandbox_talker')
        self.pub = self.create_publisher(Int64, '/sandbox_chatter', 10)
        self.create_timer(0.1, lambda: self.pub.publish(Int64(data=7)))


if __name__ == '__main__':
    rclpy.init()
    rclpy.spin(Talker())
"""
CLASS_READY_S = 120.0  # a class server's start on a 2-core machine that runs other suites too
KEY_A = 97  # keyboard_msgs/msg/Key's KEY_A, as the page sends it


@dataclass
class World:
    app: App
    token: str
    name: str  # the world's, as the class server named it

    def headers(self) -> dict[str, str]:
        return {"Authorization": f"Bearer {self.token}"}

    def get(self, path: str) -> httpx.Response:
        return HTTP.get(self.app.url + path, headers=self.headers(), timeout=10.0)

    def post(self, path: str, body: dict[str, object]) -> httpx.Response:
        return HTTP.post(self.app.url + path, json=body, headers=self.headers(), timeout=30.0)

    def stop(self, group: str) -> None:
        HTTP.delete(f"{self.app.url}/api/launches/{group}", headers=self.headers(), timeout=30.0)


@dataclass
class Class:
    root: Path
    ada: World  # sandboxed
    bob: World  # sandboxed, the same class
    cy: World  # on the unsandboxed server


def join(app: App, name: str) -> World:
    reply = HTTP.post(f"{app.url}/api/classroom/join", json={"name": name, "code": CODE}, timeout=30)
    assert reply.status_code == 201, reply.text
    return World(app, reply.json()["token"], reply.json()["world"])


def class_server(root: Path, name: str, *options: str) -> App:
    logs = root / name
    logs.mkdir()
    return App(logs, "--classroom", "--class-code", CODE, "--launch", str(root / "world.launch"),
               "--no-foxglove", *options, cwd=root, ready_s=CLASS_READY_S)  # fmt: skip


@pytest.fixture(scope="module")
def klass(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Class]:
    root = tmp_path_factory.mktemp("sandbox")
    (root / "world.launch").write_text(WORLD_LAUNCH)
    # A file of the server's, and a folder beside the workspaces.
    (root / "class-token.txt").write_text("the instructor's token\n")
    (root / "outside").mkdir()
    (root / "outside").chmod(0o777)  # writable by any uid: only the sandbox keeps a node out
    os.environ[SECRET_ENV] = "a secret of the server's"
    apps: list[App] = []
    try:
        # One after the other: two starting at once each take twice as long on a loaded machine.
        apps.append(class_server(root, "sandboxed"))
        apps.append(class_server(root, "unsandboxed", "--student-code", "unsandboxed"))
        ada, bob, cy = join(apps[0], "Ada"), join(apps[0], "Bob"), join(apps[1], "Cy")
        for world in (ada, cy):
            fill_workspace(world_workspace(root, world))
        (world_workspace(root, bob) / "notes.txt").write_text("another student's work\n")
        yield Class(root, ada, bob, cy)
    finally:
        os.environ.pop(SECRET_ENV, None)
        for app in apps:
            app.stop()


def world_workspace(root: Path, world: World) -> Path:
    """A world's workspace on its class server (``workspaces/<world>`` in the server's folder)."""
    workspace = root / "workspaces" / world.name
    workspace.mkdir(parents=True, exist_ok=True)
    return workspace


def fill_workspace(workspace: Path) -> None:
    """The handout's packages and the probe package."""
    shutil.copytree(EXAMPLES, workspace, dirs_exist_ok=True)
    (workspace / "src" / "probe").mkdir(exist_ok=True)
    shutil.copy(HERE / "probe_node.py", workspace / "src" / "probe" / "probe_node.py")
    (workspace / "src" / "probe" / "talker.py").write_text(TALKER.lstrip())


def run(world: World, executable: str, **parameters: str) -> str:
    """Run a node of the probe package; its group id."""
    started = world.post("/api/run", {"package": "probe", "executable": executable, "parameters": parameters})
    assert started.status_code == 201, started.text
    return str(started.json()["id"])


def output_of(world: World, group: str) -> list[str]:
    """Every line the run's process printed, once it has ended."""

    def ended() -> list[str] | None:
        reply = world.get(f"/api/launches/{group}/output").json()
        (node,) = reply["group"]["nodes"]
        if node["state"] in ("waiting", "running"):  # waiting: its turn to start has not come
            return None
        return [line for process in reply["processes"] for line in process["lines"]] or [f"exit {node}"]

    try:
        return wait_until(ended, f"{group} to end", 60.0, poll_s=0.2)
    finally:
        world.stop(group)


def probe_line(world: World, check: str, arg: str = "") -> str:
    lines = output_of(world, run(world, "probe_node.py", check=check, arg=arg))
    found = [line for line in lines if line.startswith(f"PROBE {check} ")]
    assert found, lines
    return found[0]


def blocked_sandboxed_works_unsandboxed(klass: Class, check: str, arg: str) -> None:
    assert probe_line(klass.cy, check, arg).startswith(f"PROBE {check} ok"), "the control failed"
    line = probe_line(klass.ada, check, arg)
    assert line.startswith(f"PROBE {check} blocked"), line


def test_sandbox_another_worlds_workspace_cannot_be_read(klass: Class) -> None:
    blocked_sandboxed_works_unsandboxed(
        klass, "read", str(world_workspace(klass.root, klass.bob) / "notes.txt")
    )


def test_sandbox_server_files_cannot_be_read(klass: Class) -> None:
    blocked_sandboxed_works_unsandboxed(klass, "read", str(klass.root / "class-token.txt"))
    blocked_sandboxed_works_unsandboxed(klass, "read", str(REPO / "pyproject.toml"))


def test_sandbox_server_environment_is_not_the_nodes(klass: Class) -> None:
    blocked_sandboxed_works_unsandboxed(klass, "env", SECRET_ENV)


def test_sandbox_no_tcp_not_even_the_servers_own_port(klass: Class) -> None:
    blocked_sandboxed_works_unsandboxed(klass, "tcp", str(klass.ada.app.port))


def test_sandbox_names_do_not_resolve(klass: Class) -> None:
    blocked_sandboxed_works_unsandboxed(klass, "dns", "localhost")


def test_sandbox_cannot_fork_past_its_process_limit(klass: Class) -> None:
    blocked_sandboxed_works_unsandboxed(klass, "fork", "")


def test_sandbox_cannot_write_outside_its_workspace_but_writes_inside(klass: Class) -> None:
    blocked_sandboxed_works_unsandboxed(klass, "write", str(klass.root / "outside" / "note.txt"))
    inside = world_workspace(klass.root, klass.ada) / "src" / "probe" / "note.txt"
    assert probe_line(klass.ada, "write", str(inside)).startswith("PROBE write ok")
    assert inside.read_text() == "written by a student's node\n"


def test_sandbox_node_over_its_memory_limit_is_killed_with_a_clear_line(klass: Class) -> None:
    assert probe_line(klass.cy, "memory").startswith("PROBE memory ok held 768 MiB")
    lines = output_of(klass.ada, run(klass.ada, "probe_node.py", check="memory"))
    assert "node killed: memory limit 512 MiB" in lines, lines
    assert not any(line.startswith("PROBE memory ok") for line in lines), lines


def node_names(world: World) -> set[str]:
    return {str(n["name"]) for n in world.get("/api/nodes").json()}


def test_sandbox_node_runs_below_the_worlds_with_its_sessions_group(klass: Class) -> None:
    """bubblewrap gives the node a session of its own, where a niceness alone would count only
    against the session's own processes (server/processes/priority.py): its session's scheduling
    group is lowered with it. An unsandboxed node runs as it was started."""
    nice = SandboxSettings().nice
    group = str(nice) if Path("/proc/self/autogroup").exists() else "none"
    own = os.getpriority(os.PRIO_PROCESS, 0)
    assert probe_line(klass.ada, "priority") == f"PROBE priority ok nice {min(19, own + nice)} group {group}"
    assert probe_line(klass.cy, "priority").startswith(f"PROBE priority ok nice {own} ")


def test_sandbox_node_reaches_its_own_world_only_and_stops(klass: Class) -> None:
    group = run(klass.ada, "talker.py")
    try:
        wait_until(lambda: "/sandbox_talker" in node_names(klass.ada), "the talker in Ada's graph", 60.0)
        wait_until(
            lambda: (
                (klass.ada.get("/api/topics/sandbox_chatter").json().get("latest") or {}).get("data") == 7
            ),
            "its messages in Ada's world",
            30.0,
        )
        # Bob's world, on the same router, sees neither the node nor its topic; a marker of Bob's own
        # (his world's pressure node) proves his graph is read.
        names = node_names(klass.bob)
        assert "/pressure" in names and "/sandbox_talker" not in names, names
        assert klass.bob.get("/api/topics/sandbox_chatter").status_code == 404
    finally:
        klass.ada.stop(group)
    # Stop ends the sandboxed node: it leaves its world's graph.
    wait_until(lambda: "/sandbox_talker" not in node_names(klass.ada), "the stopped talker to leave", 30.0)


def test_sandbox_handout_keyboard_manager_runs_and_its_messages_reach_its_world(klass: Class) -> None:
    started = klass.ada.post("/api/run", {"package": "rocketship", "executable": "keyboard_manager.py"})
    assert started.status_code == 201, started.text
    group = str(started.json()["id"])
    try:

        def aborted() -> bool:
            topic = klass.ada.get("/api/topics/abort_takeoff")
            latest = topic.json().get("latest") if topic.status_code == 200 else None
            if not (latest and latest["data"]):
                # again, until the new process's subscription has its route
                klass.ada.post("/api/publish", {"topic": "/keydown", "msg": {"code": KEY_A}})
                return False
            return True

        wait_until(aborted, "the sandboxed keyboard manager's /abort_takeoff to turn true", 60.0, poll_s=0.5)
        lines = klass.ada.get(f"/api/launches/{group}/output").json()["processes"][0]["lines"]
        assert "a key was pressed!" in lines, lines
    finally:
        klass.ada.stop(group)
