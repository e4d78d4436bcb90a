"""The class's own ROS domain: every world's topics under the world's name (``/ada/uav/sensors/gps``),
as ROS 2's domain_bridge with a namespace per world. An independent ROS 2-over-Zenoh peer
(zenoh-ros2-sdk, in its own process) logs in with what ``GET /api/zenoh/join`` gives the
instructor, and sees, watches and flies the worlds by those names; the class server runs as a
process of its own, and both are ended by their ids."""

from __future__ import annotations

import asyncio
import json
import os
import re
import shlex
import struct
import subprocess
import sys
import time
from collections.abc import Iterator
from typing import Any

import httpx
import pytest
import zenoh
from handshake import handshake_refusal, handshake_status
from interop.conftest import definitions, service_text
from mcap.records import Schema as McapSchema
from mcap_ros2.decoder import DecoderFactory
from ros_reference import rihs
from support.app import REPO, App, JsonProcess, free_port, instructor_token
from support.forked_cli import cli_command
from support.http import HTTP
from websockets.sync.client import connect

from api.errors import CloseCode
from node_runtime.transport.acl import Credentials
from node_runtime.transport.config import ZenohSettings
from node_runtime.transport.session import build_config

CODE = "GRAPH7"
POSE, VECTOR = "geometry_msgs/msg/PoseStamped", "geometry_msgs/msg/Vector3"


class Class:
    def __init__(self, app: App) -> None:
        self.app = app
        self.instructor = instructor_token(app.log_tail(10**6))
        found = re.search(
            r"Foxglove, every world as /<world>/\.\.\.: ws://127\.0\.0\.1:(\d+)/", app.log_tail(10**6)
        )
        assert found, "the class server printed no Foxglove line"
        self.foxglove_port = int(found.group(1))
        found = re.search(
            r"rosbridge, every world as /<world>/\.\.\.: ws://127\.0\.0\.1:(\d+)/", app.log_tail(10**6)
        )
        assert found, "the class server printed no rosbridge line"
        self.rosbridge_port = int(found.group(1))
        self.tokens: dict[str, str] = {}

    def call(self, method: str, path: str, token: str | None = None, **kwargs: Any) -> httpx.Response:
        headers = {"Authorization": f"Bearer {token or self.instructor}", **kwargs.pop("headers", {})}
        return HTTP.request(method, self.app.url + path, headers=headers, timeout=10.0, **kwargs)

    def world(self, name: str) -> dict[str, Any]:
        worlds = self.call("GET", "/api/classroom/worlds").json()["worlds"]
        return next(w for w in worlds if w["world"] == name)

    def drone(self, world: str) -> list[float] | None:
        drone: list[float] | None = self.world(world)["drone"]
        return drone

    def rocket(self, world: str) -> str:
        phase: str = self.world(world)["rocket"]["phase"]
        return phase

    def bridged(self) -> dict[str, list[str]]:
        reply = self.call("GET", "/api/classroom/graph")
        assert reply.status_code == 200, reply.text
        topics: dict[str, list[str]] = reply.json()["topics"]
        return topics


@pytest.fixture(scope="module")
def school(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Class]:
    root = tmp_path_factory.mktemp("class_graph")
    app = App(
        root,
        "--classroom",
        "--class-code",
        CODE,
        "--launch",
        "all",
        "--foxglove-port",
        str(free_port()),
        "--rosbridge-port",
        str(free_port()),
    )
    try:
        school = Class(app)
        for name in ("Ada", "Bob"):
            reply = HTTP.post(f"{app.url}/api/classroom/join", json={"name": name, "code": CODE}, timeout=30)
            assert reply.status_code == 201, reply.text
            school.tokens[reply.json()["world"]] = reply.json()["token"]
        yield school
    finally:
        app.stop()


def ros2lab_env(school: Class, token: str) -> dict[str, str]:
    """What ``eval "$(ros2lab env)"`` would export, with ``token`` as ROS2LAB_TOKEN."""
    done = subprocess.run(
        cli_command("--url", school.app.url, "env"),
        env={**os.environ, "ROS2LAB_TOKEN": token},
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert done.returncode == 0, done.stderr
    exports = [shlex.split(line) for line in done.stdout.splitlines()]
    assert all(words[0] == "export" and len(words) == 2 for words in exports), done.stdout
    return dict(words[1].split("=", 1) for words in exports)


@pytest.fixture(scope="module")
def peer(school: Class) -> Iterator[JsonProcess]:
    """The instructor's ROS 2 tool, on the class's own graph, in what ``ros2lab env`` exports."""
    env = ros2lab_env(school, school.instructor)
    peer = JsonProcess(
        [
            sys.executable,
            str(REPO / "tests" / "interop" / "sdk_peer.py"),
            "--router",
            school.app.router,
            "--override",
            env["ZENOH_CONFIG_OVERRIDE"],
        ],
        env={"ROS_DOMAIN_ID": env["ROS_DOMAIN_ID"]},
    )
    try:
        peer.expect(lambda e: e.get("event") == "ready", "the peer to start")
        peer.send(cmd="define", types=definitions(POSE, VECTOR))
        yield peer
    finally:
        peer.stop()


def test_the_instructor_naming_no_world_joins_the_class_domain(school: Class) -> None:
    join = school.call("GET", "/api/zenoh/join").json()
    assert (join["domain_id"], join["user"]) == (0, "ros2lab-class")
    assert join["env"]["ROS_DOMAIN_ID"] == "0"
    named = school.call("GET", "/api/zenoh/join", headers={"X-Lab-World": "bob"}).json()
    assert named["domain_id"] == 2 and named["user"].startswith("ros2lab-world-2-")
    # A student's token always gives their own world, never the class's graph.
    own = school.call("GET", "/api/zenoh/join", school.tokens["ada"]).json()
    assert own["domain_id"] == 1 and own["user"].startswith("ros2lab-world-1-")
    assert school.call("GET", "/api/classroom/graph", school.tokens["ada"]).status_code == 403


def test_ros2lab_env_exports_the_graph_a_token_joins(school: Class) -> None:
    instructor, ada = ros2lab_env(school, school.instructor), ros2lab_env(school, school.tokens["ada"])
    assert instructor["RMW_IMPLEMENTATION"] == ada["RMW_IMPLEMENTATION"] == "rmw_zenoh_cpp"
    assert (instructor["ROS_DOMAIN_ID"], ada["ROS_DOMAIN_ID"]) == ("0", "1")
    assert 'user="ros2lab-class"' in instructor["ZENOH_CONFIG_OVERRIDE"]
    assert 'user="ros2lab-world-1-' in ada["ZENOH_CONFIG_OVERRIDE"]
    refused = subprocess.run(
        cli_command("--url", school.app.url, "env"),
        env={k: v for k, v in os.environ.items() if k != "ROS2LAB_TOKEN"},
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert refused.returncode == 1 and "join the class first" in refused.stderr, refused.stderr


def test_every_worlds_topics_show_under_its_name_in_the_class_domain(
    school: Class, peer: JsonProcess
) -> None:
    def listed() -> dict[str, list[str]]:
        peer.send(cmd="topics")
        return dict(peer.expect(lambda e: e.get("event") == "topics", "the class's topics")["topics"])

    school.app.wait_for(lambda: "/bob/uav/sensors/gps" in listed(), "Bob's GPS in the class domain")
    topics = listed()
    for world in ("ada", "bob"):
        assert topics[f"/{world}/uav/sensors/gps"] == [POSE]
        assert topics[f"/{world}/uav/input/position"] == [VECTOR]
    assert "/uav/sensors/gps" not in topics  # the class's own domain holds no world's own names
    peer.send(cmd="topic_info", topic="/ada/uav/sensors/gps")
    info = peer.expect(lambda e: e.get("event") == "topic_info", "topic info")
    # The world publishes its GPS and subscribes to it (the controller): both cross, by the bridge.
    assert info["nodes"] == ["domain_bridge", "domain_bridge"]
    assert "in /ada/uav/input/position" in school.bridged()["ada"]


def test_the_instructor_watches_one_world_and_flies_it_while_the_other_stays(
    school: Class, peer: JsonProcess
) -> None:
    assert "out /ada/uav/sensors/gps" in school.bridged()["ada"]  # nobody watches yet: nothing crosses
    peer.send(cmd="subscribe", topic="/ada/uav/sensors/gps", type=POSE, hash=rihs(POSE))
    is_ada = lambda e: e.get("topic") == "/ada/uav/sensors/gps"  # noqa: E731
    peer.expect(is_ada, "Ada's GPS through the class domain")
    assert "out* /ada/uav/sensors/gps" in school.bridged()["ada"]
    assert "out /bob/uav/sensors/gps" in school.bridged()["bob"]  # Bob's is not watched: it stays home

    def ada_goes() -> bool:
        peer.send(
            cmd="publish",
            topic="/ada/uav/input/position",
            type=VECTOR,
            hash=rihs(VECTOR),
            msg={"x": 5.0, "y": 5.0, "z": 10.0},
            node="teacher",
        )
        position = school.drone("ada")
        return position is not None and min(position[0], position[1]) > 2.0

    school.app.wait_for(ada_goes, "Ada's drone flying toward the instructor's setpoint", 60.0)
    bob = school.drone("bob")  # hovering where the fly launch holds a drone: over its start
    assert bob is not None and max(abs(bob[0]), abs(bob[1])) < 0.5, bob
    # What the peer hears is Ada's own GPS: the same pose as her world's latest, but for the
    # moments of flight between them.
    latest = school.call("GET", "/api/topics/uav/sensors/gps", school.tokens["ada"]).json()["latest"]
    heard = peer.newest(is_ada)
    assert heard is not None
    assert abs(heard["msg"]["pose"]["position"]["z"] - latest["pose"]["position"]["z"]) < 1.0
    graph = school.call("GET", "/api/classroom/graph").json()
    assert graph["samples_out"] > 0 and graph["samples_in"] > 0


def test_the_instructor_calls_one_worlds_service_by_its_name_and_only_that_world_answers(
    school: Class, peer: JsonProcess
) -> None:
    for world in ("ada", "bob"):  # back on the pad first: the module's earlier tests may outlast a countdown
        reply = school.call("POST", "/api/rocket/reset", school.tokens[world])
        assert reply.status_code == 200, reply.text
    for world in ("ada", "bob"):  # both students abort their rockets before lift-off
        reply = school.call(
            "POST",
            "/api/publish",
            school.tokens[world],
            json={"topic": "/abort_takeoff", "msg": {"data": True}},
        )
        assert reply.status_code == 200, reply.text
    for world in ("ada", "bob"):
        school.app.wait_for(lambda w=world: school.rocket(w) == "aborted", f"{world}'s rocket aborted")
    school.app.wait_for(
        lambda: "srv /ada/rocket/reset" in school.bridged().get("ada", []), "Ada's reset bridged"
    )
    request, response = service_text("std_srvs/srv/Trigger")
    peer.send(
        cmd="call",
        service="/ada/rocket/reset",
        type="std_srvs/srv/Trigger",
        request=request,
        response=response,
        hash=rihs("std_srvs/srv/Trigger"),
    )
    reply = peer.expect(lambda e: e.get("event") == "reply", "Ada's world's answer")
    assert reply["msg"] == {"success": True, "message": "rocket back on the pad"}
    assert school.rocket("ada") in ("ready", "counting down")  # back on the pad
    assert school.rocket("bob") == "aborted"  # Bob's world was not asked
    graph = school.call("GET", "/api/classroom/graph").json()
    assert graph["calls"] >= 1 and graph["calls_refused"] == 0


def test_the_instructors_foxglove_shows_every_world_under_its_name(school: Class) -> None:
    url = f"ws://127.0.0.1:{school.foxglove_port}/?token={school.instructor}"
    with connect(url, subprotocols=["foxglove.sdk.v1"], open_timeout=10, max_size=None) as ws:
        channels: dict[str, dict[str, Any]] = {}
        deadline = time.monotonic() + 20
        wanted = {"/ada/uav/sensors/gps", "/bob/uav/sensors/gps", "/bob/countdown"}
        while not wanted <= set(channels):
            assert time.monotonic() < deadline, f"channels so far: {sorted(channels)}"
            try:
                frame = ws.recv(timeout=max(0.05, deadline - time.monotonic()))
            except TimeoutError:
                continue
            if isinstance(frame, str) and (msg := json.loads(frame))["op"] == "advertise":
                channels.update({c["topic"]: c for c in msg["channels"]})
        assert not any(name.startswith("/uav/") for name in channels), "a world's names bare, unnamespaced"
        gps = channels["/bob/uav/sensors/gps"]
        assert (gps["encoding"], gps["schemaName"]) == ("cdr", POSE)
        ws.send(json.dumps({"op": "subscribe", "subscriptions": [{"id": 9, "channelId": gps["id"]}]}))
        deadline = time.monotonic() + 20
        while True:  # Bob's GPS crosses into the class domain now that someone watches it
            assert time.monotonic() < deadline, "no sample of Bob's GPS reached Foxglove"
            try:
                frame = ws.recv(timeout=max(0.05, deadline - time.monotonic()))
            except TimeoutError:
                continue
            if isinstance(frame, bytes):
                break
    assert struct.unpack_from("<BI", frame) == (0x01, 9)
    schema = McapSchema(id=1, name=POSE, encoding="ros2msg", data=gps["schema"].encode())
    pose = DecoderFactory().decoder_for("cdr", schema)(frame[13:])  # type: ignore[misc]
    bob = school.call("GET", "/api/topics/uav/sensors/gps", school.tokens["bob"]).json()["latest"]
    assert abs(pose.pose.position.z - bob["pose"]["position"]["z"]) < 1.0  # Bob's own, hovering


def test_a_setpoint_from_the_class_foxglove_keeps_the_worlds_limits(school: Class) -> None:
    url = f"ws://127.0.0.1:{school.foxglove_port}/?token={school.instructor}"
    setpoints = lambda: school.call(  # noqa: E731
        "GET", "/api/topics/uav/input/position", school.tokens["bob"]
    ).json()["publish_count"]
    before = setpoints()
    with connect(url, subprotocols=["foxglove.sdk.v1"], open_timeout=10, max_size=None) as ws:
        channel = {"id": 1, "topic": "/bob/uav/input/position", "encoding": "json", "schemaName": VECTOR}
        ws.send(json.dumps({"op": "advertise", "channels": [channel]}))
        ws.send(
            struct.pack("<BI", 0x01, 1) + b'{"x": 50000.0, "y": 0.0, "z": 1.0}'
        )  # past the limit of 10 km
        deadline = time.monotonic() + 10
        while True:
            assert time.monotonic() < deadline, "no status said the setpoint was refused"
            try:
                frame = ws.recv(timeout=max(0.05, deadline - time.monotonic()))
            except TimeoutError:
                continue
            if isinstance(frame, str) and (msg := json.loads(frame))["op"] == "status":
                break
        assert "/bob/uav/input/position" in msg["message"] and "out of range" in msg["message"], msg
        assert setpoints() == before  # nothing reached Bob's world

        def lands_in_bob() -> bool:  # one inside the arena goes through, into Bob's world only
            ws.send(struct.pack("<BI", 0x01, 1) + b'{"x": 0.0, "y": 0.0, "z": 1.5}')
            return bool(setpoints() > before)

        school.app.wait_for(lands_in_bob, "the instructor's setpoint in Bob's world")


def test_the_class_foxglove_port_refuses_a_student_and_another_site(school: Class) -> None:
    port = school.foxglove_port

    def refusal(path: str, *headers: tuple[str, str], host: str = f"127.0.0.1:{port}") -> int:
        return asyncio.run(handshake_refusal(port, path, (("Host", host), *headers)))

    assert refusal("/") == CloseCode.UNAUTHORIZED
    assert refusal(f"/?token={school.tokens['ada']}") == CloseCode.UNAUTHORIZED  # a student's: her world only
    assert refusal("/", ("Authorization", f"Bearer {school.tokens['bob']}")) == CloseCode.UNAUTHORIZED
    assert refusal(f"/?token={school.instructor}", ("Origin", "https://evil.example")) == CloseCode.FORBIDDEN
    assert (
        refusal(f"/?token={school.instructor}", host="evil.example") == CloseCode.MISDIRECTED
    )  # DNS rebinding


def rosbridge_reply(ws: Any, wanted: Any, what: str) -> dict[str, Any]:
    """The first JSON frame ``wanted`` accepts, within 20 s."""
    deadline = time.monotonic() + 20
    while time.monotonic() < deadline:
        try:
            frame = json.loads(ws.recv(timeout=max(0.05, deadline - time.monotonic())))
        except TimeoutError:
            continue
        if wanted(frame):
            return dict(frame)
    pytest.fail(f"no {what} in 20 s")


def test_the_instructors_rosbridge_sees_every_world_and_keeps_its_limits(school: Class) -> None:
    """The class's --rosbridge-port: rosapi lists every world's topics under its name, a subscription
    without a type gets Bob's GPS, and a setpoint keeps the limits of Bob's own /uav/input/position."""
    url = f"ws://127.0.0.1:{school.rosbridge_port}/?token={school.instructor}"
    with connect(url, open_timeout=10) as ws:
        ws.send(json.dumps({"op": "set_level", "level": "error"}))  # status frames, as roslibpy asks
        deadline = time.monotonic() + 20
        wanted = {"/ada/uav/sensors/gps", "/bob/uav/sensors/gps", "/bob/countdown"}
        while True:
            ws.send(json.dumps({"op": "call_service", "id": "t", "service": "/rosapi/topics", "args": {}}))
            topics = rosbridge_reply(ws, lambda f: f.get("op") == "service_response", "rosapi's topics")
            if wanted <= set(topics["values"]["topics"]):
                break
            assert time.monotonic() < deadline, f"topics so far: {topics['values']['topics']}"
            time.sleep(0.2)
        assert not any(name.startswith("/uav/") for name in topics["values"]["topics"])
        ws.send(
            json.dumps({"op": "subscribe", "id": "g", "topic": "/bob/uav/sensors/gps", "throttle_rate": 100})
        )
        sample = rosbridge_reply(ws, lambda f: f.get("op") == "publish", "sample of Bob's GPS")
        assert sample["topic"] == "/bob/uav/sensors/gps"
        bob = school.call("GET", "/api/topics/uav/sensors/gps", school.tokens["bob"]).json()["latest"]
        assert abs(sample["msg"]["pose"]["position"]["z"] - bob["pose"]["position"]["z"]) < 1.0
        ws.send(json.dumps({"op": "unsubscribe", "id": "g", "topic": "/bob/uav/sensors/gps"}))

        setpoints = lambda: school.call(  # noqa: E731
            "GET", "/api/topics/uav/input/position", school.tokens["bob"]
        ).json()["publish_count"]
        before = setpoints()
        far = {"op": "publish", "topic": "/bob/uav/input/position", "msg": {"x": 50000.0, "y": 0.0, "z": 1.0}}
        ws.send(json.dumps(far))  # past the limit of 10 km
        refused = rosbridge_reply(ws, lambda f: f.get("op") == "status", "status for the far setpoint")
        assert refused["level"] == "error" and "out of range" in refused["msg"], refused
        assert setpoints() == before  # nothing reached Bob's world

        def lands_in_bob() -> bool:  # one inside the arena goes through, into Bob's world only
            near = {
                "op": "publish",
                "topic": "/bob/uav/input/position",
                "msg": {"x": 0.0, "y": 0.0, "z": 1.5},
            }
            ws.send(json.dumps(near))
            return bool(setpoints() > before)

        school.app.wait_for(lands_in_bob, "the instructor's rosbridge setpoint in Bob's world")


def test_the_class_rosbridge_refuses_a_student_and_another_site(school: Class) -> None:
    port, app_port = school.rosbridge_port, school.app.port

    def refusal(at: int, path: str, *headers: tuple[str, str], host: str | None = None) -> int:
        return asyncio.run(handshake_refusal(at, path, (("Host", host or f"127.0.0.1:{at}"), *headers)))

    assert refusal(port, "/") == CloseCode.UNAUTHORIZED
    assert refusal(port, f"/?token={school.tokens['ada']}") == CloseCode.UNAUTHORIZED  # her world only
    assert (
        refusal(port, f"/?token={school.instructor}", ("Origin", "https://evil.example"))
        == CloseCode.FORBIDDEN
    )
    assert refusal(port, f"/?token={school.instructor}", host="evil.example") == CloseCode.MISDIRECTED
    # On the app's own port the path is the instructor's too; a student keeps /rosbridge, her world's.
    assert refusal(app_port, f"/class/rosbridge?token={school.tokens['ada']}") == CloseCode.FORBIDDEN
    assert refusal(app_port, "/class/rosbridge") == CloseCode.UNAUTHORIZED
    host = ("Host", f"127.0.0.1:{app_port}")
    assert asyncio.run(handshake_status(app_port, f"/rosbridge?token={school.tokens['ada']}", (host,))) == 101


def test_a_students_login_does_not_reach_the_class_domain(school: Class) -> None:
    join = school.call("GET", "/api/zenoh/join", school.tokens["ada"]).json()
    settings = ZenohSettings(
        mode="client",
        listen=(),
        connect=(f"tcp/{school.app.router}",),
        login=Credentials(join["user"], join["password"]),
    )
    with zenoh.open(build_config(settings)) as session:
        own = [r for r in session.liveliness().get("@ros2_lv/1/**", timeout=5) if r.ok]
        assert own  # her own world's graph answers her
        assert [r for r in session.liveliness().get("@ros2_lv/0/**", timeout=2) if r.ok] == []


def test_a_removed_world_leaves_the_class_domain(school: Class) -> None:
    assert school.call("DELETE", "/api/classroom/worlds/bob").status_code == 200
    school.app.wait_for(lambda: "bob" not in school.bridged(), "Bob's topics gone from the class domain")
    # The removal reopens the class router without Bob's login, which drops every session for a
    # moment; Ada's world reconnects by itself and is bridged again, and Bob's never comes back.
    school.app.wait_for(lambda: "ada" in school.bridged(), "Ada's topics back in the class domain")
    assert "bob" not in school.bridged()
