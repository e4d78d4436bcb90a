"""A class server on Zenoh: each world joins the class's router in a ROS domain of its own, so a
student's node process (``ros2lab run`` with the student's token) joins their world only. The
server and the node run as processes of their own, on loopback, and are ended by their ids."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import httpx
import pytest
import zenoh
from support.app import App, end, instructor_token
from support.http import HTTP

from node_runtime.msgs import Key
from node_runtime.msgs.wire import dds_type_name, serialize, type_hash
from node_runtime.process.priority import session_group_nice
from node_runtime.transport.acl import ClassAuth, Credentials
from node_runtime.transport.attachment import Attachment
from node_runtime.transport.config import ZenohSettings
from node_runtime.transport.keys import data_key
from node_runtime.transport.session import build_config
from server.host.settings import SandboxSettings

CODE = "ZEN042"
FLOOD = 20_000  # samples, ten seconds' worth of what a world takes from other processes
TALKER = """
import rclpy
from rclpy.node import Node
from std_msgs.msg import Int64


class Talker(Node):
    def __init__(self):
        super().__init__('talker')
        self.pub = self.create_publisher(Int64, '/chatter', 10)
        self.count = 0
        self.create_timer(0.1, self.tick)

    def tick(self):
        self.count += 1
        self.pub.publish(Int64(data=self.count))


if __name__ == '__main__':
    rclpy.init()
    rclpy.spin(Talker())
"""


@pytest.fixture(scope="module")
def classroom(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[App, Path, dict[str, str]]]:
    root = tmp_path_factory.mktemp("classroom_zenoh")
    talker = root / "workspace" / "src" / "demo" / "demo" / "talker.py"
    talker.parent.mkdir(parents=True)
    talker.write_text(TALKER.lstrip())
    app = App(root, "--classroom", "--class-code", CODE, "--launch", "rocket", "start_delay:=600", cwd=root)
    try:
        tokens = {}
        for name in ("Ada", "Bob"):
            reply = HTTP.post(f"{app.url}/api/classroom/join", json={"name": name, "code": CODE}, timeout=30)
            assert reply.status_code == 201, reply.text
            tokens[reply.json()["world"]] = reply.json()["token"]
        yield app, root, tokens
    finally:
        app.stop()


def get(app: App, token: str, path: str) -> httpx.Response:
    return HTTP.get(app.url + path, headers={"Authorization": f"Bearer {token}"}, timeout=5.0)


def login_of(app: App, token: str) -> Credentials:
    join = get(app, token, "/api/zenoh/join").json()
    return Credentials(join["user"], join["password"])


def open_on(app: App, login: Credentials | None) -> zenoh.Session:
    """A client of the class's router, logged in as ``login`` (or not at all)."""
    settings = ZenohSettings(mode="client", listen=(), connect=(f"tcp/{app.router}",), login=login)
    return zenoh.open(build_config(settings))


def test_each_world_has_a_ros_domain_of_its_own(classroom: tuple[App, Path, dict[str, str]]) -> None:
    app, _root, tokens = classroom
    domains = {w: get(app, t, "/api/health").json()["zenoh"]["domain_id"] for w, t in tokens.items()}
    assert domains == {"ada": 1, "bob": 2}


def ada_nodes(app: App, tokens: dict[str, str]) -> set[str]:
    return {n["name"] for n in get(app, tokens["ada"], "/api/nodes").json()}


@contextmanager
def adas_talker(app: App, root: Path, tokens: dict[str, str]) -> Iterator[subprocess.Popen[str]]:
    """``ros2lab run demo talker.py`` with Ada's token, as she types it; Ctrl-C at the end, and
    the talker gone from her world."""
    env = {**os.environ, "ROS2LAB_TOKEN": tokens["ada"]}
    env.pop("ROS_DOMAIN_ID", None)
    run = subprocess.Popen(
        [sys.executable, "-m", "server", "--url", app.url, "run", "demo", "talker.py"],
        cwd=root,
        env=env,
        text=True,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )
    try:
        yield run
    finally:
        run.send_signal(signal.SIGINT)
        try:
            run.communicate(timeout=15)
        except subprocess.TimeoutExpired:
            end(run)
    app.wait_for(
        lambda: "/talker" not in ada_nodes(app, tokens), "the talker gone from Ada's world once it stopped"
    )


# The talker runs at the sandbox's niceness (19) in a scheduling group of its own, so beside the
# parallel part's busy workers it gets a hundredth of a core and its start is a matter of luck:
# the tests that start it run in the timing part, alone.
@pytest.mark.timing
def test_a_students_node_process_joins_their_world_only(classroom: tuple[App, Path, dict[str, str]]) -> None:
    app, root, tokens = classroom
    with adas_talker(app, root, tokens):

        def ada_hears() -> bool:
            rate: dict[str, Any] = get(app, tokens["ada"], "/api/hz/chatter?window=5").json()
            return rate.get("window") == 5

        app.wait_for(ada_hears, "Ada's world hearing her talker's /chatter")
        nodes = {n["name"]: n for n in get(app, tokens["ada"], "/api/nodes").json()}
        assert nodes["/talker"]["location"] != "app"  # another process, on the class's Zenoh graph
        assert get(app, tokens["bob"], "/api/topics/chatter").status_code == 404
        assert "/talker" not in {n["name"] for n in get(app, tokens["bob"], "/api/nodes").json()}


def children_of(pid: int) -> list[int]:
    found = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                stat = (entry / "stat").read_text()
            except OSError:  # it ended meanwhile
                continue
            if int(stat.rsplit(")", 1)[1].split()[1]) == pid:
                found.append(int(entry.name))
    return found


@pytest.mark.timing
def test_a_students_node_process_runs_below_the_worlds(classroom: tuple[App, Path, dict[str, str]]) -> None:
    """The class server's join asks for its sandbox's niceness; ``ros2lab run`` gives it to the
    node and, the node leading a session of its own, to its session's scheduling group: a niceness
    alone counts only within a session (node_runtime/process/priority.py)."""
    app, root, tokens = classroom
    nice = SandboxSettings().nice
    assert get(app, tokens["ada"], "/api/zenoh/join").json()["nice"] == nice
    ours_before = session_group_nice(os.getpid())
    with adas_talker(app, root, tokens) as run:
        app.wait_for(lambda: "/talker" in ada_nodes(app, tokens), "the talker in Ada's world")
        (node,) = children_of(run.pid)
        assert os.getpriority(os.PRIO_PROCESS, node) == min(19, os.getpriority(os.PRIO_PROCESS, 0) + nice)
        assert os.getsid(node) == node != os.getsid(0)
        if Path(f"/proc/{node}/autogroup").exists():  # a kernel with autogroup scheduling
            assert session_group_nice(node) == nice  # a new session's group, even beside the root's
            assert session_group_nice(os.getpid()) == ours_before  # ours as it was


def test_a_student_gets_their_worlds_login_and_the_environment_that_uses_it(
    classroom: tuple[App, Path, dict[str, str]],
) -> None:
    app, _root, tokens = classroom
    ada, bob = (get(app, tokens[w], "/api/zenoh/join").json() for w in ("ada", "bob"))
    assert (ada["router"], ada["domain_id"]) == (f"tcp/{app.router}", 1)
    assert ada["user"].startswith("ros2lab-world-1-") and bob["user"].startswith("ros2lab-world-2-")
    assert bob["domain_id"] == 2
    assert len({ada["password"], bob["password"], tokens["ada"], tokens["bob"]}) == 4
    assert ada["env"]["ROS_DOMAIN_ID"] == "1"
    override = ada["env"]["ZENOH_CONFIG_OVERRIDE"]
    assert f'transport/auth/usrpwd/password="{ada["password"]}"' in override and 'mode="client"' in override
    assert get(app, tokens["ada"], "/api/health").json()["zenoh"]["login"] is True
    assert HTTP.get(app.url + "/api/zenoh/join", timeout=5.0).status_code == 401  # no token, no login


def test_the_class_router_lets_in_no_one_without_a_login(classroom: tuple[App, Path, dict[str, str]]) -> None:
    app, _root, tokens = classroom
    with pytest.raises(zenoh.ZError):
        open_on(app, None)
    wrong = Credentials(login_of(app, tokens["ada"]).user, "0" * 40)
    with pytest.raises(zenoh.ZError):
        open_on(app, wrong)


def test_a_worlds_login_reaches_its_own_domain_only(classroom: tuple[App, Path, dict[str, str]]) -> None:
    app, _root, tokens = classroom
    ada, bob = login_of(app, tokens["ada"]), login_of(app, tokens["bob"])
    heard: list[str] = []
    with open_on(app, ClassAuth(instructor_token(app.log_tail(10**6))).class_credentials()) as watcher:
        subscriber = watcher.declare_subscriber("**", lambda sample: heard.append(str(sample.key_expr)))
        with open_on(app, ada) as ada_session, open_on(app, bob) as bob_session:
            # Each world's graph is visible to its own login, and only to it.
            assert any(
                str(r.ok.key_expr).startswith("@ros2_lv/1/")
                for r in ada_session.liveliness().get("@ros2_lv/1/**", timeout=5)
                if r.ok
            )
            assert any(
                str(r.ok.key_expr).startswith("@ros2_lv/2/")
                for r in bob_session.liveliness().get("@ros2_lv/2/**", timeout=5)
                if r.ok
            )
            assert [r for r in ada_session.liveliness().get("@ros2_lv/2/**", timeout=2) if r.ok] == []
            # Samples in order through the one router: Ada's put in Bob's domain, then a marker in
            # her own. The watcher hears the marker, and nothing before it.
            ada_session.put("2/chatter/x", b"from ada")
            ada_session.put("1/chatter/marker", b"marker")
            bob_session.put("2/chatter/own", b"from bob")
            deadline = time.monotonic() + 10
            while not {"1/chatter/marker", "2/chatter/own"} <= set(heard) and time.monotonic() < deadline:
                time.sleep(0.02)
        subscriber.undeclare()
        assert "1/chatter/marker" in heard and "2/chatter/own" in heard, heard
        assert "2/chatter/x" not in heard
        # Nor does Ada hear Bob's domain: her subscription to it is declared before the one to her
        # own, so once her own hears the watcher, the router has refused the other.
        ada_heard: list[str] = []
        with open_on(app, ada) as ada_session:
            for keys in ("2/**", "1/**"):
                ada_session.declare_subscriber(keys, lambda sample: ada_heard.append(str(sample.key_expr)))
            deadline = time.monotonic() + 10
            while "1/chatter/watcher" not in ada_heard and time.monotonic() < deadline:
                watcher.put("2/chatter/watcher", b"for bob")
                watcher.put("1/chatter/watcher", b"for ada")
                time.sleep(0.05)
    assert "1/chatter/watcher" in ada_heard
    assert not [key for key in ada_heard if key.startswith("2/")], ada_heard


def test_a_students_zenoh_flood_is_cut_at_their_worlds_door(
    classroom: tuple[App, Path, dict[str, str]],
) -> None:
    # A process with Ada's login floods her world's /keydown far beyond what a world takes from
    # other processes (WorldLimits.samples_hz, 2000 a second): the rest is dropped as it
    # arrives, counted in her world's health, and Bob's world takes nothing of it.
    app, _root, tokens = classroom

    def zenoh_of(world: str) -> dict[str, Any]:
        status: dict[str, Any] = get(app, tokens[world], "/api/health").json()["zenoh"]
        return status

    bob_before = zenoh_of("bob")
    key = data_key(1, "/keydown", dds_type_name(Key.TYPE), type_hash(Key.TYPE))
    payload = serialize(Key(code=ord("x")))
    with open_on(app, login_of(app, tokens["ada"])) as flooder:
        publisher = flooder.declare_publisher(key, congestion_control=zenoh.CongestionControl.BLOCK)
        deadline = time.monotonic() + 10
        while not publisher.matching_status.matching and time.monotonic() < deadline:
            time.sleep(0.02)
        for seq in range(1, FLOOD + 1):
            publisher.put(payload, attachment=Attachment(seq, time.time_ns(), bytes(16)).pack())
        # Sent in well under a few seconds, so at most a few seconds' worth got in.
        app.wait_for(
            lambda: zenoh_of("ada")["dropped_over_rate"] >= FLOOD // 2, "Ada's flood cut at her world's door"
        )
    bob_after = zenoh_of("bob")
    assert bob_after["dropped_over_rate"] == 0
    assert bob_after["received"] == bob_before["received"]
