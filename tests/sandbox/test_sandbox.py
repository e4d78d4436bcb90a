"""Students' nodes on a live class server run sandboxed: each thing the sandbox blocks is tried by a
student's node run through ``POST /api/run`` on a class server that sandboxes (the default) and
on one started with ``--student-code unsandboxed``, where it must work, so no test passes by
accident. Both servers run as processes of their own on loopback, shared by the module, and are
ended by their ids."""

from __future__ import annotations

import functools
import os
import re
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

from server.base.loop_priority import scheduling_of
from server.host.processes import cgroups
from server.host.settings import SandboxSettings
from server.services.launch.commands import NOT_HERE


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
    return App(
        logs,
        "--classroom",
        "--class-code",
        CODE,
        "--launch",
        str(root / "world.launch"),
        "--no-foxglove",
        *options,
        cwd=root,
        ready_s=CLASS_READY_S,
    )


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


def swap_begun(world: World, group: str) -> bool:
    """The swapping node said it started (or that it could not)."""
    reply = world.get(f"/api/launches/{group}/output").json()
    lines = [line for process in reply["processes"] for line in process["lines"]]
    return any(line.startswith(("PROBE swap started", "PROBE swap blocked")) for line in lines)


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


def test_sandbox_cannot_write_outside_its_workspace(klass: Class) -> None:
    blocked_sandboxed_works_unsandboxed(klass, "write", str(klass.root / "outside" / "note.txt"))


def test_sandbox_workspace_is_read_only_to_a_node_which_writes_in_its_tmp(klass: Class) -> None:
    """A node never changes the tree the API serves (no link, no race, no disk filled through it):
    its workspace is read-only inside, and its /tmp takes what it writes."""
    for world in (klass.cy, klass.ada):  # the unsandboxed control first
        inside = world_workspace(klass.root, world) / "src" / "probe" / "note.txt"
        line = probe_line(world, "write", str(inside))
        assert line.startswith("PROBE write blocked" if world is klass.ada else "PROBE write ok"), line
        assert inside.exists() is (world is klass.cy)
    assert probe_line(klass.ada, "write", "/tmp/note.txt").startswith("PROBE write ok")
    assert probe_line(klass.ada, "read", "src/probe/probe_node.py").startswith(
        "PROBE read ok"
    )  # its own files


def test_sandbox_node_over_its_memory_limit_is_killed_with_a_clear_line(klass: Class) -> None:
    assert probe_line(klass.cy, "memory").startswith("PROBE memory ok held 768 MiB")
    lines = output_of(klass.ada, run(klass.ada, "probe_node.py", check="memory"))
    assert "node killed: memory limit 512 MiB" in lines, lines
    assert not any(line.startswith("PROBE memory ok") for line in lines), lines


def node_names(world: World) -> set[str]:
    return {str(n["name"]) for n in world.get("/api/nodes").json()}


def test_sandbox_node_runs_below_the_worlds_with_its_sessions_group(klass: Class) -> None:
    """bubblewrap gives the node a session of its own, where a niceness alone would count only
    against the session's own processes (node_runtime/process/priority.py): its session's scheduling
    group is lowered with it. An unsandboxed node runs as it was started."""
    nice = SandboxSettings().nice
    group = str(nice) if Path("/proc/self/autogroup").exists() else "none"
    own = os.getpriority(os.PRIO_PROCESS, 0)
    assert probe_line(klass.ada, "priority") == f"PROBE priority ok nice {min(19, own + nice)} group {group}"
    assert probe_line(klass.cy, "priority").startswith(f"PROBE priority ok nice {own} ")


def test_sandbox_node_starts_below_the_real_time_loop_and_cannot_take_its_class(klass: Class) -> None:
    """Both class servers run their worlds' loop in the real-time class (server/base/loop_priority.py,
    as root); a node they start never inherits it. A node on the unsandboxed server runs as the
    server's user and may take it; a sandboxed one, an ordinary user with no real-time limit
    (node_runtime/process/confinement.py), may not, so it can never get ahead of the worlds."""
    for world in (klass.ada, klass.cy):
        assert scheduling_of(world.app.proc.pid) == "realtime", world.name  # the server's loop thread
    assert probe_line(klass.cy, "realtime") == "PROBE realtime ok started normal, took SCHED_FIFO 1"
    line = probe_line(klass.ada, "realtime")
    assert line.startswith("PROBE realtime blocked started normal, SCHED_FIFO refused"), line


def test_sandbox_node_cannot_leave_the_nodes_cpu_group(klass: Class) -> None:
    """The nodes' one CPU group weighs them below the worlds (server/host/processes/cgroups.py): a
    node that moves itself into the group the server runs in would take a session's full share
    again. It cannot (no /sys inside, not root); run as the server's user, the same write works."""
    if os.geteuid() != 0:
        pytest.skip("only root moves a process between control groups: the control would fail")
    base = cgroups._version_1_cpu(cgroups._own_groups(), cgroups._mounts())
    if base is None:
        assert os.environ.get("CI") != "true", "no cgroup v1 cpu hierarchy on the CI machine"
        pytest.skip("no cgroup v1 cpu hierarchy this process may write")
    blocked_sandboxed_works_unsandboxed(klass, "cgroup", str(base / "cgroup.procs"))


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


# Attacks by a student who reads the code: each tried on the sandboxing server, and on the
# unsandboxed one where the blocked step must work (so the test cannot pass by accident).


def put_file(world: World, path: str, text: str) -> None:
    saved = HTTP.put(
        f"{world.app.url}/api/workspace/files/{path}",
        json={"text": text},
        headers=world.headers(),
        timeout=30.0,
    )
    assert saved.status_code in (200, 201), saved.text


READS = 150  # the student's reads while their node swaps
SHADOW = "print('SHADOW RAN as', __import__('os').getuid(), flush=True)\n"


def test_sandbox_a_shadow_runner_in_the_workspace_never_runs(klass: Class) -> None:
    """``node_runtime/process/runner.py`` (and ``rclpy``, ``std_msgs``) saved at the workspace's root
    and beside the node: the lab's runner and packages run, never these, on both servers."""
    shadows = [
        "server/__init__.py",
        "server/host/processes/__init__.py",
        "node_runtime/process/runner.py",
        "rclpy/__init__.py",
        "std_msgs/__init__.py",
        "src/probe/rclpy/__init__.py",
        "src/probe/std_msgs/__init__.py",
        "src/probe/server/__init__.py",
    ]
    node = (
        "import rclpy\nimport std_msgs.msg\nimport node_runtime.process.runner as runner\n"
        "print('FILES', rclpy.__file__, std_msgs.msg.__file__, runner.__file__, flush=True)\n"
        "if __name__ == '__main__':\n    pass\n"
    )
    for world in (klass.cy, klass.ada):
        for path in shadows:
            put_file(world, path, SHADOW)
        put_file(world, "src/probe/lab_first.py", node)
        try:
            lines = output_of(world, run(world, "lab_first.py"))
            assert not any("SHADOW" in line for line in lines), lines
            (files,) = [line.split()[1:] for line in lines if line.startswith("FILES ")]
            assert all(Path(f).is_relative_to(REPO) and "workspaces" not in Path(f).parts for f in files), (
                files
            )
        finally:
            for path in (
                "server",
                "rclpy",
                "std_msgs",
                "src/probe/rclpy",
                "src/probe/std_msgs",
                "src/probe/server",
            ):
                HTTP.delete(
                    f"{world.app.url}/api/workspace/files/{path}", headers=world.headers(), timeout=30.0
                )


def test_sandbox_node_starts_with_no_capability_no_root_no_new_privileges_and_seccomp(klass: Class) -> None:
    fields = dict(item.split("=") for item in probe_line(klass.ada, "status").split()[3:])
    assert fields["CapEff"] == "0000000000000000" and fields["Uid"] != "0", fields
    assert fields["NoNewPrivs"] == "1" and fields["Seccomp"] == "2", fields
    control = dict(item.split("=") for item in probe_line(klass.cy, "status").split()[3:])
    if os.geteuid() == 0:  # the unsandboxed node is the root server's own user
        assert control["CapEff"] != "0000000000000000" and control["Seccomp"] == "0", control


def test_sandbox_files_cannot_be_opened_by_handle(klass: Class) -> None:
    if os.geteuid() != 0:
        pytest.skip("opening by handle needs CAP_DAC_READ_SEARCH: the control works only under a root server")
    blocked_sandboxed_works_unsandboxed(klass, "handle", "/")


def test_sandbox_shared_memory_and_tmpfs_are_counted(klass: Class) -> None:
    """Shared mappings and tmpfs pages escape RLIMIT_DATA: a cgroup (or the address space) counts
    them, and /dev/shm is capped."""
    blocked_sandboxed_works_unsandboxed(klass, "shm", "/dev/shm/ros2lab-probe")
    # Past what counts it: the 512 MiB of a memory cgroup, or where the machine gives none (the
    # server's banner says which), the address space's 2 GiB.
    counted_whole = "counted whole" in klass.ada.app.log_path.read_text(errors="replace")
    mib = "768" if counted_whole else "2304"
    assert probe_line(klass.cy, "shared", mib).startswith(f"PROBE shared ok touched {mib} MiB")
    lines = output_of(klass.ada, run(klass.ada, "probe_node.py", check="shared", arg=mib))
    assert not any(line.startswith("PROBE shared ok") for line in lines), lines
    assert "node killed: memory limit 512 MiB" in lines or any("blocked" in line for line in lines), lines


def test_sandbox_a_link_at_the_saves_temporary_name_is_not_followed(klass: Class) -> None:
    """A node plants ``.victim.py.saving`` pointing at another student's file, then its student
    saves ``victim.py``: sandboxed, the node cannot plant it; unsandboxed it can, and the save
    still writes its own file only."""
    for world in (klass.cy, klass.ada):
        ws = world_workspace(klass.root, world)
        victim = ws / "src" / "probe" / "victim.py"
        put_file(world, "src/probe/victim.py", "# mine\n")
        target = world_workspace(klass.root, klass.bob) / "notes.txt"
        before = target.read_text()
        planted = ws / "src" / "probe" / ".victim.py.saving"
        line = probe_line(world, "link", f"{planted}={target}")
        assert line.startswith("PROBE link ok" if world is klass.cy else "PROBE link blocked"), line
        put_file(world, "src/probe/victim.py", "# saved again\n")
        assert victim.read_text() == "# saved again\n" and not victim.is_symlink()
        assert target.read_text() == before
        planted.unlink(missing_ok=True)


def test_sandbox_reads_never_follow_a_link_a_node_swaps_in(klass: Class) -> None:
    """Unsandboxed, a node swaps its file for a link to another student's file and back while its
    student reads it: no answer holds the other file. Sandboxed, it cannot swap at all."""
    secret = world_workspace(klass.root, klass.bob) / "notes.txt"
    for world in (klass.cy, klass.ada):
        put_file(world, "src/probe/swapped.txt", "my own text\n")
        where = world_workspace(klass.root, world) / "src" / "probe" / "swapped.txt"
        group = run(world, "probe_node.py", check="swap", arg=f"{where}={secret}")
        answers: dict[int, int] = {}
        try:
            wait_until(functools.partial(swap_begun, world, group), "the node to start swapping", 60.0)
            for _ in range(READS):  # bounded; the node swaps for 4 s
                reply = world.get("/api/workspace/files/src/probe/swapped.txt")
                answers[reply.status_code] = answers.get(reply.status_code, 0) + 1
                assert "another student's work" not in reply.text, reply.text
        finally:
            lines = output_of(world, group)
        assert set(answers) <= {200, 404, 422}, answers
        if world is klass.cy:
            assert any(line.startswith("PROBE swap ok") for line in lines), lines
        else:
            assert any(line.startswith("PROBE swap blocked") for line in lines), lines
            assert answers == {200: READS}, answers


def remove_nested(folder: Path) -> None:
    """Remove a folder however deep it goes, without recursion (pytest's own clean-up of its
    temporary folders would hit Python's recursion limit on what a node nested)."""
    stack = [folder]
    while stack:
        try:
            entries = list(os.scandir(stack[-1]))
        except FileNotFoundError:
            stack.pop()
            continue
        inner = [Path(e.path) for e in entries if e.is_dir(follow_symlinks=False)]
        for entry in entries:
            if not entry.is_dir(follow_symlinks=False):
                os.unlink(entry.path)
        if inner:
            stack.extend(inner)
        else:
            stack.pop().rmdir()


def test_sandbox_a_node_cannot_fill_or_nest_its_workspace_and_the_api_survives_a_deep_one(
    klass: Class,
) -> None:
    for world in (klass.cy, klass.ada):
        folder = world_workspace(klass.root, world) / "src" / "probe" / "deep"
        try:
            line = probe_line(world, "deep", str(folder))
            assert line.startswith("PROBE deep ok" if world is klass.cy else "PROBE deep blocked"), line
            # Whatever is on the disk, the API answers: the unsandboxed node made 1,100 folders.
            tree = world.get("/api/workspace/files")
            assert tree.status_code == 200, tree.text
            assert tree.json()["too_deep"] == (1 if world is klass.cy else 0), tree.json()
            assert world.get("/api/workspace/archive").status_code == 200
            put_file(world, "src/probe/after_deep.py", "# still saves\n")
            removed = HTTP.delete(
                f"{world.app.url}/api/workspace/files/src/probe/deep", headers=world.headers(), timeout=60.0
            )
            assert removed.status_code in ((200, 204) if world is klass.cy else (404,)), removed.text
            assert not folder.exists()
        finally:
            remove_nested(folder)
    assert probe_line(klass.ada, "write", "/tmp/fits.txt").startswith("PROBE write ok")


LAUNCH_PROBE = """import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import ExecuteProcess, LogInfo


def generate_launch_description():
    target = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'written_by_launch.txt')
    try:
        with open(target, 'w') as out:
            out.write('a launch file wrote this')
        wrote = 'ok'
    except OSError as exc:
        wrote = 'blocked ' + type(exc).__name__
    share = get_package_share_directory('probe')
    return LaunchDescription([LogInfo(msg=f'PROBE launch uid {os.getuid()} write {wrote} share {share}'),
                              ExecuteProcess(cmd=['ros2', 'param', 'set', '/sim', 'background_r', '120'])])
"""


def test_sandbox_a_python_launch_file_is_evaluated_in_the_sandbox(klass: Class) -> None:
    """A .launch.py's generate_launch_description() is a student's code: where students' nodes are
    sandboxed it runs in the sandbox (another uid, the workspace read-only); the same file on the
    unsandboxed server runs as the server's user and writes."""
    probes: dict[str, str] = {}
    for world in (klass.cy, klass.ada):  # the unsandboxed control first
        launch_dir = world_workspace(klass.root, world) / "src" / "probe" / "launch"
        launch_dir.mkdir(exist_ok=True)
        (launch_dir / "probe.launch.py").write_text(LAUNCH_PROBE)
        started = world.post("/api/launch", {"package": "probe", "file": "probe.launch.py"})
        assert started.status_code == 201, started.text
        world.stop(started.json()["id"])
        (probe,) = [m for m in started.json()["messages"] if "PROBE launch" in m]
        share = f" share {launch_dir.parent.resolve()}"  # its package found from inside, too
        assert probe.endswith(share), probe
        probes[world.name] = probe.removesuffix(share)
        assert (launch_dir / "written_by_launch.txt").exists() is (world is klass.cy)
        # A class server runs no command of a launch file, sandboxed or not: one line says so.
        assert started.json()["messages"][-1] == (
            f"[ERROR] [launch]: {launch_dir / 'probe.launch.py'}:18: not run: 'ros2 param set /sim background_r "
            f"120': {NOT_HERE}"
        )
    assert probes[klass.cy.name] == f"[INFO] [launch.user]: PROBE launch uid {os.getuid()} write ok"
    sandboxed = re.fullmatch(
        r"\[INFO\] \[launch\.user\]: PROBE launch uid (\d+) write blocked (OSError|PermissionError)",
        probes[klass.ada.name],
    )
    assert sandboxed is not None, probes
    assert int(sandboxed.group(1)) != os.getuid(), probes  # the world's uid (as root), or the sandbox's
