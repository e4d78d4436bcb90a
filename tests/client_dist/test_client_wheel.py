"""The client distribution (client/pyproject.toml) stands alone: its wheel holds what a node process
imports and nothing of the web server; installed by itself in a fresh venv (no system packages,
nothing of the app's), a student's node file runs in it and talks both ways with a running lab."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
import time
import venv
import zipfile
from collections.abc import Iterator
from pathlib import Path

import pytest
from support.app import REPO, App, end
from websockets.sync.client import connect

INSTALL_S = 600.0  # pip from its cache and the machine's wheel folders; bounded all the same
WEB_SIDE = ("fastapi", "starlette", "uvicorn", "viser", "pydantic", "server", "sim", "api", "httpx", "mcap")

RELAY = """
import rclpy
from rclpy.node import Node
from std_msgs.msg import String


class Relay(Node):
    def __init__(self):
        super().__init__('laptop_relay')
        self.pub = self.create_publisher(String, '/from_laptop', 10)
        self.create_subscription(String, '/to_laptop', self.relay, 10)

    def relay(self, msg):
        self.pub.publish(String(data='laptop heard ' + msg.data))


if __name__ == '__main__':
    rclpy.init()
    try:
        rclpy.spin(Relay())
    except KeyboardInterrupt:
        pass
    finally:
        rclpy.try_shutdown()
"""


def run(args: list[str], cwd: Path, timeout_s: float = INSTALL_S) -> str:
    done = subprocess.run(args, cwd=cwd, capture_output=True, text=True, timeout=timeout_s, env=_clean_env())
    assert done.returncode == 0, f"{' '.join(args)} failed:\n{done.stdout[-3000:]}\n{done.stderr[-3000:]}"
    return done.stdout


def _clean_env(extra: dict[str, str] | None = None) -> dict[str, str]:
    """This environment without anything that would put the repository on the path."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV", "PYTHONHOME")}
    return {**env, **(extra or {})}


@pytest.fixture(scope="module")
def wheel(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("wheel")
    run(
        [
            sys.executable,
            "-m",
            "pip",
            "wheel",
            "--no-deps",
            "--no-build-isolation",
            "-w",
            str(out),
            str(REPO / "client"),
        ],
        out,
    )
    (built,) = out.glob("teleop_lab_client-*.whl")
    return built


@pytest.fixture(scope="module")
def laptop(wheel: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A fresh venv (no system site-packages) with the client wheel and its declared dependencies."""
    root = tmp_path_factory.mktemp("laptop")
    venv.EnvBuilder(with_pip=False, system_site_packages=False).create(root / "venv")
    python = root / "venv" / "bin" / "python"
    # This venv's pip installs into that one (no pip of its own to bootstrap; nothing compiled ahead).
    run(
        [
            sys.executable,
            "-m",
            "pip",
            "--python",
            str(python),
            "install",
            "--disable-pip-version-check",
            "--no-compile",
            "-q",
            str(wheel),
        ],
        root,
    )
    return python


def _shipped_files(folder: Path) -> set[str]:
    """Every file under ``folder`` a wheel built from the tree ships, relative to ``folder``'s
    parent: all but bytecode and the machine's own dot-files (the set-up's stamp, the parse cache)."""
    return {
        p.relative_to(folder.parent).as_posix()
        for p in folder.rglob("*")
        if p.is_file()
        and "__pycache__" not in p.parts
        and p.suffix != ".pyc"
        and not any(part.startswith(".") for part in p.relative_to(folder).parts)
    }


def test_wheel_holds_the_client_and_nothing_of_the_web_server(wheel: Path) -> None:
    names = set(zipfile.ZipFile(wheel).namelist())
    tops = {n.split("/")[0] for n in names if not n.startswith("teleop_lab_client-")}
    client_packages = {p.parent.name for p in (REPO / "client").glob("*/__init__.py")}
    assert len(client_packages) > 30 and "rclpy" in client_packages
    assert tops == client_packages | {"node_runtime"}
    # Every file of the client's package folders, at the top of the wheel.
    client_files = {name for package in client_packages for name in _shipped_files(REPO / "client" / package)}
    assert not client_files - names
    # The whole node runtime, its interface definitions with it: the lab's own, and ROS 2's, which
    # the set-up extracts into a folder git ignores.
    runtime = _shipped_files(REPO / "node_runtime")
    assert not runtime - names
    definitions = {
        p.relative_to(REPO).as_posix() for p in (REPO / "node_runtime/msgs/interfaces").glob("*/*/*")
    }
    ros = {p.relative_to(REPO).as_posix() for p in (REPO / "node_runtime/msgs/ros_interfaces").glob("*/*/*")}
    assert not definitions - names and not ros - names and len(ros) > 150  # ROS 2's, as the set-up took them
    assert {"node_runtime/process/runner.py", "node_runtime/transport/bridge.py", "rclpy/node.py"} <= names
    assert {"node_runtime/msgs/generated/std_msgs.py", "node_runtime/msgs/ros_packages.txt"} <= names
    assert "node_runtime/msgs/interfaces/keyboard_msgs/msg/Key.msg" in names
    assert "node_runtime/msgs/ros_interfaces/std_msgs/msg/String.msg" in names
    # What it ships is the tree's: no bytecode, and every runtime file is one of the checkout's.
    assert not [n for n in names if "__pycache__" in n.split("/") or n.endswith(".pyc")]
    assert all((REPO / n).is_file() for n in names if n.startswith("node_runtime/"))
    assert not {"pyproject.toml", "README.md"} & names  # the client folder's own files stay behind
    # Nothing of the web server, the API or the sims.
    assert not [n for n in names if n.split("/")[0] in ("server", "api", "sim")]
    for app_side in (
        "server/app.py",
        "server/world/lab.py",
        "server/host/settings/__init__.py",
        "server/host/processes/supervisor.py",
        "server/packages/rocketship/keyboard_manager.py",
    ):
        assert app_side not in names
    assert not any(
        n.startswith(
            (
                "server/peripherals/viewer/",
                "server/services/bridges/",
                "server/classroom/",
                "server/host/settings/",
            )
        )
        for n in names
    )
    metadata = zipfile.ZipFile(wheel).read("teleop_lab_client-0.1.0.dist-info/METADATA").decode()
    assert "Requires-Dist: eclipse-zenoh==1.10.2" in metadata
    assert not any(dep in metadata.lower() for dep in ("fastapi", "uvicorn", "viser"))


def test_importing_the_client_loads_nothing_of_the_web_server(laptop: Path, tmp_path: Path) -> None:
    probe = textwrap.dedent("""
        import json, sys
        import rclpy
        from rclpy.node import Node
        from std_msgs.msg import Bool
        from keyboard_msgs.msg import Key
        from geometry_msgs.msg import Vector3
        from rclpy.action import ActionClient, ActionServer
        from rclpy.parameter_client import AsyncParameterClient
        from example_interfaces.action import Fibonacci
        from action_tutorials_interfaces.action import Fibonacci as TutorialFibonacci
        from nav_msgs.msg import Odometry
        from sensor_msgs_py import point_cloud2
        assert point_cloud2.read_points_list(point_cloud2.create_cloud_xyz32(Odometry().header, [(1, 2, 3)])) == [(1, 2, 3)]
        from tf2_ros import Buffer, StaticTransformBroadcaster, TransformListener
        import node_runtime.process.runner
        print(json.dumps({"modules": sorted(sys.modules), "rclpy": rclpy.__file__}))
    """)
    out = json.loads(run([str(laptop), "-c", probe], tmp_path, 60.0))
    tops = {m.split(".")[0] for m in out["modules"]}
    assert not tops & set(WEB_SIDE), tops & set(WEB_SIDE)
    assert "zenoh" in tops and "rclpy" in tops  # what it does load: the client itself
    assert str(laptop.parents[1]) in out["rclpy"]  # from the fresh venv, not the repository
    # Nothing of the web side is even installed there.
    absent = ["fastapi", "uvicorn", "viser", "starlette", "server", "sim", "api"]
    missing = run(
        [
            str(laptop),
            "-c",
            "import importlib.util as u, json, sys; "
            "print(json.dumps([m for m in sys.argv[1:] if u.find_spec(m) is None]))",
            *absent,
        ],
        tmp_path,
        60.0,
    )
    assert json.loads(missing) == absent


@pytest.fixture(scope="module")
def lab(tmp_path_factory: pytest.TempPathFactory) -> Iterator[App]:
    workdir = tmp_path_factory.mktemp("lab")
    app = App(workdir, "--launch", "rocket", "start_delay:=3600", cwd=workdir)
    try:
        yield app
    finally:
        app.stop()


def test_a_node_file_in_the_client_venv_talks_both_ways_with_a_lab(
    laptop: Path, lab: App, tmp_path: Path
) -> None:
    node_file = tmp_path / "relay.py"
    node_file.write_text(RELAY)
    env = _clean_env(lab.get("/api/zenoh/join")["env"])
    proc = subprocess.Popen(
        [str(laptop), str(node_file)],
        cwd=tmp_path,
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
    )
    try:
        lab.wait_for(
            lambda: (
                any(n["name"] == "/laptop_relay" for n in lab.get("/api/nodes")) or proc.poll() is not None
            ),
            "the laptop's node in the lab's graph",
        )
        assert proc.poll() is None, proc.communicate()[0]
        with connect(f"ws://127.0.0.1:{lab.port}/ws/topics/from_laptop?type=std_msgs/msg/String") as echo:
            deadline = time.monotonic() + 20.0
            heard = None
            i = 0
            while heard is None and time.monotonic() < deadline:
                # Until the relay's subscription is matched, as for any new ROS 2 subscription.
                sent = lab.post(
                    "/api/publish",
                    {"topic": "/to_laptop", "msg": {"data": f"hi {i}"}, "type": "std_msgs/msg/String"},
                )
                assert sent.status_code == 200, sent.text
                i += 1
                try:
                    heard = json.loads(echo.recv(timeout=0.5))
                except TimeoutError:
                    continue
        assert heard is not None, f"nothing came back from the laptop's node ({i} sent)"
        assert heard["msg"]["data"].startswith("laptop heard hi ")
    finally:
        end(proc)
        if proc.stdout is not None:
            proc.stdout.close()
