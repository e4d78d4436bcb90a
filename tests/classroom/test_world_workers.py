"""World workers (``ros2lab world-worker``): a class server places new worlds where the load is
lowest (itself or a worker on its Zenoh router) and keeps serving every student's calls; a world
on a worker answers through the class server like a local one.

A class server, two workers and a stranger (a worker started with another token, which the class's
router does not let in) run as processes of their own on loopback, and are ended by their ids.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import math
import os
import queue
import subprocess
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import httpx
import pytest
import websockets
import zenoh
from support.app import App, WorldWorker, instructor_token, wait_for_workers
from support.forked_cli import cli_command
from support.http import HTTP

from api.errors import CloseCode
from node_runtime.msgs.wire import dds_type_name, deserialize, type_hash
from node_runtime.transport.acl import ClassAuth, Credentials
from node_runtime.transport.attachment import Attachment
from node_runtime.transport.config import ZenohSettings
from node_runtime.transport.keys import data_key
from node_runtime.transport.session import build_config
from server.classroom.workers import CONTROL_PREFIX, hello_request, worker_api_token

CODE = "WRK042"
STUDENTS = ("Ada", "Bob", "Cy", "Dee")
TARGET = (5.0, 5.0, 10.0)
NEAR_M = 1.0
FLY_S = 40.0
KEY_UP = 273  # keyboard_msgs/Key code (SDL) of ArrowUp
HELLO_S = 3.0
KEY_WAIT_S = 30.0  # the key crosses the class server's proxy and a WebSocket to worker wb


@dataclass
class Class:
    app: App
    instructor: str
    workers: dict[str, WorldWorker]
    tokens: dict[str, str]  # world → its student's token

    def get(self, path: str, token: str, **headers: str) -> httpx.Response:
        return HTTP.get(
            self.app.url + path, headers={"Authorization": f"Bearer {token}", **headers}, timeout=10
        )

    def post(self, path: str, token: str, body: Any = None) -> httpx.Response:
        return HTTP.post(
            self.app.url + path, headers={"Authorization": f"Bearer {token}"}, json=body, timeout=30
        )

    def worlds(self) -> dict[str, dict[str, Any]]:
        reply = self.get("/api/classroom/worlds", self.instructor)
        assert reply.status_code == 200, reply.text
        return {w["world"]: w for w in reply.json()["worlds"]}

    def position(self, world: str) -> tuple[float, float, float]:
        latest = self.get("/api/topics/uav/sensors/gps", self.tokens[world]).json()["latest"]
        p = latest["pose"]["position"]
        return p["x"], p["y"], p["z"]


@pytest.fixture(scope="module")
def klass(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Class]:
    root = tmp_path_factory.mktemp("world_workers")
    # The class server hosts one world itself; each worker up to three.
    app = App(
        root, "--classroom", "--class-code", CODE, "--launch", "fly", "--local-worlds", "1", "--no-foxglove"
    )
    workers: dict[str, WorldWorker] = {}
    try:
        instructor = instructor_token(app.log_tail(10**6))
        for wid in ("wa", "wb"):
            workers[wid] = WorldWorker(root, app.router, instructor, wid, "--max-worlds", "3")
        # A process on the same router that does not know the instructor's token.
        workers["stranger"] = WorldWorker(root, app.router, "not-the-instructors-token", "stranger")
        wait_for_workers(app.url, instructor, {"wa", "wb"})
        tokens: dict[str, str] = {}
        for name in STUDENTS:  # one at a time: each placement sees the one before
            reply = HTTP.post(f"{app.url}/api/classroom/join", json={"name": name, "code": CODE}, timeout=60)
            assert reply.status_code == 201, reply.text
            tokens[reply.json()["world"]] = reply.json()["token"]
        yield Class(app, instructor, workers, tokens)
    finally:
        for worker in workers.values():
            worker.stop()
        app.stop()


def test_the_class_server_trusts_only_workers_that_know_its_token(klass: Class) -> None:
    listed = klass.get("/api/classroom/workers", klass.instructor).json()
    assert {w["id"] for w in listed["workers"]} == {"wa", "wb"}  # not the stranger
    assert listed["local"]["max_worlds"] == 1
    assert "ros2lab world-worker --connect" in klass.app.log_tail(10**6)  # the banner says how to add one
    # The stranger never got in: the class's router refused its login, and it said why.
    stranger = klass.workers["stranger"]
    assert stranger.proc.wait(timeout=30) == 2
    assert "ROS2LAB_TOKEN the instructor's token" in stranger.log_tail(), stranger.log_tail()


def hellos(klass: Class, login: Credentials, payload: bytes) -> list[Any]:
    """The answers to a hello asked on the class's router, logged in as ``login``."""
    settings = ZenohSettings(mode="client", listen=(), connect=(f"tcp/{klass.app.router}",), login=login)
    with zenoh.open(build_config(settings)) as session:
        return [r.ok for r in session.get(f"{CONTROL_PREFIX}/*", payload=payload, timeout=HELLO_S) if r.ok]


def test_each_workers_hello_carries_its_cpu_and_the_class_server_shows_its_own(klass: Class) -> None:
    listed = klass.get("/api/classroom/workers", klass.instructor).json()
    for place in [listed["local"], *listed["workers"]]:
        cpu = place["cpu"]
        assert cpu["cores"] >= 1 and cpu["process_cores"] >= 0, place
        assert cpu["host_busy"] is None or 0 <= cpu["host_busy"] <= 1, place
    # One machine here: every place names the same one, so its busy share decides nothing between them.
    assert len({place["cpu"]["machine"] for place in [listed["local"], *listed["workers"]]}) == 1, listed
    # Each worker hosts a fly world or two, so its process has used some CPU in its last window.
    workers = {w["id"]: w for w in listed["workers"]}
    assert all(workers[wid]["cpu"]["process_cores"] > 0 for wid in ("wa", "wb")), [
        w["cpu"] for w in workers.values()
    ]


def test_a_hello_not_sealed_with_the_class_token_gets_no_answer_from_any_worker(klass: Class) -> None:
    # Even logged in as the class, an unsealed hello learns nothing: not where the workers' APIs
    # are, nor their load. The same question sealed as the class server seals it is answered.
    plain = json.dumps({"op": "hello", "nonce": "stranger"}).encode()
    sealed = hello_request(klass.instructor, "genuine")
    class_login = ClassAuth(klass.instructor).class_credentials()
    assert hellos(klass, class_login, plain) == []
    assert sorted(json.loads(r.payload.to_bytes())["id"] for r in hellos(klass, class_login, sealed)) == [
        "wa",
        "wb",
    ]
    # A student's process, logged in as their world, cannot even ask: the router keeps it in its domain.
    join = klass.get("/api/zenoh/join", klass.tokens["ada"]).json()
    assert hellos(klass, Credentials(join["user"], join["password"]), sealed) == []


def test_new_worlds_go_where_the_load_is_lowest(klass: Class) -> None:
    # Empty workers first (a tie with the empty server goes to a worker), then the server's own
    # room, then the less loaded worker; never the stranger.
    placed = {name: world["worker"] for name, world in klass.worlds().items()}
    assert placed == {"ada": "wa", "bob": "wb", "cy": None, "dee": "wa"}


def test_a_workers_world_flies_through_the_class_server(klass: Class) -> None:
    reply = klass.post(
        "/api/publish",
        klass.tokens["ada"],
        {"topic": "/uav/input/position", "msg": dict(zip("xyz", TARGET, strict=True))},
    )
    assert reply.status_code == 200, reply.text
    klass.app.wait_for(
        lambda: math.dist(klass.position("ada"), TARGET) < NEAR_M, "ada's drone at (5, 5, 10)", FLY_S
    )
    assert klass.worlds()["ada"]["drone"][2] > TARGET[2] - NEAR_M  # the instructor sees it there too
    assert klass.position("bob")[2] < 4.0  # bob's drone, on the other worker, still hovers at home


def test_a_workers_world_shows_under_its_name_in_the_class_domain(klass: Class) -> None:
    # The instructor's login on the class's own graph hears Ada's GPS, from her world on worker wa,
    # as /ada/uav/sensors/gps: what her world's latest pose says, but for the moments between.
    join = klass.get("/api/zenoh/join", klass.instructor).json()
    assert join["domain_id"] == 0
    settings = ZenohSettings(
        mode="client", listen=(), connect=(join["router"],), login=Credentials(join["user"], join["password"])
    )
    pose = "geometry_msgs/msg/PoseStamped"
    key = data_key(0, "/ada/uav/sensors/gps", dds_type_name(pose), type_hash(pose))
    heard: queue.Queue[tuple[bytes, bytes | None]] = queue.Queue(maxsize=1000)

    def keep(sample: zenoh.Sample) -> None:
        attachment = sample.attachment.to_bytes() if sample.attachment is not None else None
        with contextlib.suppress(queue.Full):
            heard.put_nowait((sample.payload.to_bytes(), attachment))

    with zenoh.open(build_config(settings)) as session:
        tokens = [str(r.ok.key_expr) for r in session.liveliness().get("@ros2_lv/0/**", timeout=5) if r.ok]
        assert any("/MP/%/%ada/domain_bridge/%ada%uav%sensors%gps/" in t for t in tokens), tokens
        subscriber = session.declare_subscriber(key, keep)
        payload, attachment = heard.get(timeout=30)
        subscriber.undeclare()
    assert attachment is not None and Attachment.unpack(attachment) is not None  # rmw_zenoh's, or dropped
    heard_at = deserialize(pose, payload).pose.position  # type: ignore[attr-defined]
    assert math.dist((heard_at.x, heard_at.y, heard_at.z), klass.position("ada")) < NEAR_M


def test_topic_echo_and_keys_reach_a_workers_world_over_websockets(klass: Class) -> None:
    def keydowns() -> tuple[int, Any]:
        reply = klass.get("/api/topics/keydown", klass.tokens["bob"])
        assert reply.status_code == 200, reply.text
        return reply.json()["publish_count"], reply.json()["latest"]

    count_before, _ = keydowns()

    async def run() -> dict[str, Any]:
        auth = {"Authorization": f"Bearer {klass.tokens['bob']}"}
        base = klass.app.url.replace("http", "ws")
        async with websockets.connect(f"{base}/ws/topics/uav/sensors/gps", additional_headers=auth) as echo:
            frame = json.loads(await asyncio.wait_for(echo.recv(), 10.0))
        async with websockets.connect(f"{base}/ws/keys", additional_headers=auth) as keys:
            # Down and up at once: the key's press reaches the world however loaded the machine
            # (a held key would be released by the 0.5 s dead-man if a heartbeat came late).
            await keys.send(json.dumps({"type": "keydown", "key": "ArrowUp", "code": "ArrowUp"}))
            await keys.send(json.dumps({"type": "keyup", "key": "ArrowUp", "code": "ArrowUp"}))
        return frame

    frame = asyncio.run(run())
    assert frame["topic"] == "/uav/sensors/gps" and "pose" in frame["msg"]
    # The keyboard node of bob's world, on worker wb, published the press on /keydown.
    klass.app.wait_for(lambda: keydowns()[0] > count_before, "bob's /keydown to carry the press", KEY_WAIT_S)
    assert keydowns()[1]["code"] == KEY_UP
    klass.app.wait_for(lambda: not klass.worlds()["bob"].get("keys_held"), "bob's key released")
    assert klass.get("/api/topics/keydown", klass.tokens["ada"]).json()["publish_count"] == 0  # not ada's


def test_one_students_token_opens_no_other_world_on_any_worker(klass: Class) -> None:
    assert klass.get("/api/topics", klass.tokens["bob"], **{"X-Lab-World": "ada"}).status_code == 403
    assert (
        HTTP.get(f"{klass.app.url}/api/topics", headers={"X-Lab-World": "ada"}, timeout=10).status_code == 401
    )

    async def other_world_socket() -> int | None:
        auth = {"Authorization": f"Bearer {klass.tokens['bob']}"}
        url = klass.app.url.replace("http", "ws") + "/ws/topics/uav/sensors/gps?world=ada"
        try:
            async with websockets.connect(url, additional_headers=auth) as ws:
                await ws.recv()
        except websockets.exceptions.ConnectionClosed as exc:
            return exc.rcvd.code if exc.rcvd is not None else None
        return None

    assert asyncio.run(other_world_socket()) == CloseCode.FORBIDDEN
    # The worker itself takes no student's token, and no student joins it directly.
    worker_url = next(
        w["url"] for w in klass.get("/api/classroom/workers", klass.instructor).json()["workers"]
    )
    direct = HTTP.get(
        f"{worker_url}/api/topics", headers={"Authorization": f"Bearer {klass.tokens['ada']}"}, timeout=10
    )
    assert direct.status_code == 401
    join = HTTP.post(f"{worker_url}/api/classroom/join", json={"name": "Eve", "code": CODE}, timeout=10)
    assert join.status_code == 403


def test_the_instructor_resets_and_removes_a_workers_world(klass: Class) -> None:
    reply = klass.post("/api/classroom/worlds/ada/reset", klass.instructor)
    assert reply.status_code == 200, reply.text
    klass.app.wait_for(lambda: klass.position("ada")[2] < 4.0, "ada's drone back near home after the reset")
    assert klass.worlds()["ada"]["resets"] == 1
    removed = HTTP.delete(
        f"{klass.app.url}/api/classroom/worlds/dee",
        headers={"Authorization": f"Bearer {klass.instructor}"},
        timeout=30,
    )
    assert removed.status_code == 200, removed.text
    assert klass.get("/api/topics", klass.tokens["dee"]).status_code == 401  # dee's token is void
    counts = {
        w["id"]: w["worlds"] for w in klass.get("/api/classroom/workers", klass.instructor).json()["workers"]
    }
    assert counts == {"wa": 1, "wb": 1}  # dee's world is gone from worker wa


def test_the_broadcast_reaches_worlds_here_and_on_workers(klass: Class) -> None:
    body = {"topic": "/uav/input/position", "msg": {"x": 0.0, "y": 0.0, "z": 2.0}}
    reply = klass.post("/api/classroom/broadcast", klass.instructor, body)
    assert reply.status_code == 200, reply.text
    assert sorted(reply.json()["reached"]) == ["ada", "bob", "cy"]


def test_a_world_a_worker_hosts_that_the_class_does_not_count_there_is_ended(klass: Class) -> None:
    # As after a removal while worker wb could not be reached: wb hosts a world the class server
    # does not count on it. Its next hello (every 2 s) finds it, and it ends there.
    wb = next(
        w for w in klass.get("/api/classroom/workers", klass.instructor).json()["workers"] if w["id"] == "wb"
    )
    as_class_server = {"Authorization": f"Bearer {worker_api_token(klass.instructor, 'wb')}"}
    body = {
        "world": "stray",
        "student": "Nobody",
        "domain_id": 200,
        "launch": "rocket",
        "launch_args": {"start_delay": "3600"},
    }
    placed = HTTP.post(f"{wb['url']}/api/classroom/host", headers=as_class_server, json=body, timeout=60)
    assert placed.status_code == 201, placed.text

    def on_wb() -> set[str]:
        reply = HTTP.get(f"{wb['url']}/api/classroom/worlds", headers=as_class_server, timeout=10)
        assert reply.status_code == 200, reply.text
        return {w["world"] for w in reply.json()["worlds"]}

    klass.app.wait_for(lambda: "stray" not in on_wb(), "worker wb to end the world the class does not count")
    assert on_wb() == {"bob"}  # the class's own world there stays
    assert "still hosts world stray" in klass.app.log_tail(10**6)
    assert klass.get("/api/topics", klass.tokens["bob"]).status_code == 200  # through the class server


def test_a_worker_needs_the_instructors_token(tmp_path: Path) -> None:
    env = {k: v for k, v in os.environ.items() if k != "ROS2LAB_TOKEN"}
    done = subprocess.run(
        cli_command("world-worker", "--connect", "tcp/127.0.0.1:1"),
        env=env,
        capture_output=True,
        text=True,
        timeout=60,
        cwd=tmp_path,
    )
    assert done.returncode == 2
    assert "ROS2LAB_TOKEN" in done.stderr
