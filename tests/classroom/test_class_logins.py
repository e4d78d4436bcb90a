"""A world's Zenoh login is its student's, not its slot's: drawn at random when the world is made,
revoked when it is removed (the router drops every open session of it and refuses it from then
on), and never valid in the next world given the same ROS domain. And a world cannot pass its
entities off as another world's in the class's own domain. Against a class server in a process
of its own, with raw Zenoh sessions from here (loopback, multicast scouting off)."""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import httpx
import pytest
import zenoh
from support.app import App, instructor_token
from support.http import HTTP
from support.wait import wait_until

from node_runtime.msgs import PoseStamped, Vector3
from node_runtime.msgs.wire import dds_type_name, serialize, type_hash
from node_runtime.transport.acl import ClassAuth, Credentials
from node_runtime.transport.attachment import Attachment
from node_runtime.transport.config import ZenohSettings
from node_runtime.transport.keys import EntityKind, EntityToken, data_key, keep_last
from node_runtime.transport.session import build_config

CODE = "LOGIN7"
POSE = (dds_type_name(PoseStamped.TYPE), type_hash(PoseStamped.TYPE))
VECTOR = (dds_type_name(Vector3.TYPE), type_hash(Vector3.TYPE))
GID = bytes(range(16))


@dataclass
class Class:
    app: App
    instructor: str
    tokens: dict[str, str] = field(default_factory=dict)

    def call(self, method: str, path: str, token: str | None = None, **kwargs: Any) -> httpx.Response:
        headers = {"Authorization": f"Bearer {token or self.instructor}"}
        return HTTP.request(method, self.app.url + path, headers=headers, timeout=30.0, **kwargs)

    def join(self, name: str) -> tuple[str, dict[str, Any]]:
        reply = HTTP.post(f"{self.app.url}/api/classroom/join", json={"name": name, "code": CODE}, timeout=30)
        assert reply.status_code == 201, reply.text
        world, token = reply.json()["world"], reply.json()["token"]
        self.tokens[world] = token
        join = self.call("GET", "/api/zenoh/join", token)
        assert join.status_code == 200, join.text
        return world, join.json()

    def drone(self, world: str) -> list[float] | None:
        worlds = self.call("GET", "/api/classroom/worlds").json()["worlds"]
        drone: list[float] | None = next(w for w in worlds if w["world"] == world)["drone"]
        return drone


@pytest.fixture(scope="module")
def school(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Class]:
    root: Path = tmp_path_factory.mktemp("class_logins")
    app = App(root, "--classroom", "--class-code", CODE, "--launch", "all")
    try:
        yield Class(app, instructor_token(app.log_tail(10**6)))
    finally:
        app.stop()


def open_on(school: Class, login: Credentials) -> Any:
    """A raw client of the class's router, logged in as ``login``."""
    settings = ZenohSettings(mode="client", listen=(), connect=(f"tcp/{school.app.router}",), login=login)
    return zenoh.open(build_config(settings))


def login_of(join: dict[str, Any]) -> Credentials:
    return Credentials(join["user"], join["password"])


class Heard:
    """Samples one subscription has received, counted from Zenoh's threads."""

    def __init__(self) -> None:
        self.payloads: list[bytes] = []
        self._lock = threading.Lock()

    def __call__(self, sample: zenoh.Sample) -> None:
        with self._lock:
            self.payloads.append(sample.payload.to_bytes())

    @property
    def count(self) -> int:
        with self._lock:
            return len(self.payloads)


def gps_key(domain_id: int, world: str = "") -> str:
    return data_key(domain_id, f"{world}/uav/sensors/gps", *POSE)


def setpoint(x: float, y: float, z: float, seq: int) -> tuple[bytes, bytes]:
    return serialize(Vector3(x=x, y=y, z=z)), Attachment(seq, time.time_ns(), GID).pack()


def test_a_removed_students_login_is_dropped_refused_and_useless_in_the_next_world(school: Class) -> None:
    _, bea = school.join("Bea")  # a student who stays: her session comes back by itself
    eve_world, eve = school.join("Eve")
    old = login_of(eve)
    heard_before, heard_bea = Heard(), Heard()
    with open_on(school, old) as session, open_on(school, login_of(bea)) as bea_session:
        session.declare_subscriber(gps_key(eve["domain_id"]), heard_before)
        bea_session.declare_subscriber(gps_key(bea["domain_id"]), heard_bea)
        wait_until(lambda: heard_before.count > 0, "Eve's own login hearing her GPS")  # it works while hers
        reply = school.call("DELETE", f"/api/classroom/worlds/{eve_world}")
        assert reply.status_code == 200, reply.text
        # The router dropped her open session: it has no router any more, and hears nothing more.
        wait_until(lambda: not session.info.routers_zid(), "the router dropping Eve's open session")
        cut, bea_cut = heard_before.count, heard_bea.count
        with pytest.raises(zenoh.ZError):  # and refuses her login from now on
            open_on(school, old).close()
        finn_world, finn = school.join("Finn")
        assert finn["domain_id"] == eve["domain_id"]  # the freed domain, given to the next student
        new = login_of(finn)
        assert new.user != old.user and new.password != old.password
        with pytest.raises(zenoh.ZError):
            open_on(school, old).close()
        # Eve's old session tries to fly Finn's drone: nothing of it reaches his world.
        received = school.call("GET", "/api/health", school.tokens[finn_world]).json()["zenoh"]["received"]
        target = data_key(finn["domain_id"], "/uav/input/position", *VECTOR)
        for seq in range(1, 21):
            payload, attachment = setpoint(-4.0, -4.0, 3.0, seq)
            session.put(target, payload, attachment=attachment)
        # Finn's own login hears his GPS and flies his drone; that is the marker Eve's session never sees.
        heard_finn = Heard()
        with open_on(school, new) as finn_session:
            finn_session.declare_subscriber(gps_key(finn["domain_id"]), heard_finn)
            publisher = finn_session.declare_publisher(target)
            wait_until(lambda: heard_finn.count >= 5, "Finn's login hearing his GPS")
            seq = 0

            def flies() -> bool:
                nonlocal seq
                seq += 1
                payload, attachment = setpoint(4.0, 4.0, 3.0, seq)
                publisher.put(payload, attachment=attachment)
                position = school.drone(finn_world)
                return position is not None and min(position[0], position[1]) > 1.0

            wait_until(flies, "Finn's drone flying to his own setpoint", 60.0)
            health = school.call("GET", "/api/health", school.tokens[finn_world]).json()["zenoh"]
            assert health["received"] - received <= seq  # his setpoints only, none of Eve's twenty
        assert heard_before.count == cut and not session.info.routers_zid()
        wait_until(lambda: heard_bea.count > bea_cut, "Bea's session back on the router, hearing her GPS")
        wait_until(
            lambda: "bea" in school.call("GET", "/api/classroom/graph").json()["topics"],
            "Bea's world in the class graph again",
        )


def test_a_name_without_its_leading_slash_does_not_pass_for_another_worlds_topic(school: Class) -> None:
    # In world ada, the topic "m/uav/sensors/gps" would be joined as /ada + m/uav/... = /adam/uav/...
    ada_world, ada = school.join("Ada")
    adam_world, _ = school.join("Adam")
    assert (ada_world, adam_world) == ("ada", "adam")
    class_login = ClassAuth(school.instructor).class_credentials()
    spoof = b"\x00\x01\x00\x00spoofed"
    with open_on(school, login_of(ada)) as student, open_on(school, class_login) as instructor:
        zid, domain = str(student.zid()), ada["domain_id"]
        declared = []
        for entity_id, (kind, topic) in enumerate(
            [
                (EntityKind.PUBLISHER, "m/uav/sensors/gps"),
                (EntityKind.SUBSCRIPTION, "m/uav/input/position"),
                (EntityKind.PUBLISHER, "/probe"),
            ],  # a valid name, last: once it shows, the others were read
            start=2,
        ):
            dds, rihs = POSE if kind is EntityKind.PUBLISHER else VECTOR
            token = EntityToken(
                domain,
                zid,
                1,
                entity_id,
                kind,
                "/",
                "spoofer",
                topic=topic,
                dds_type=dds,
                type_hash=rihs,
                qos=keep_last(10),
            )
            declared.append(student.liveliness().declare_token(token.key))

        def graph() -> dict[str, Any]:
            reply = school.call("GET", "/api/classroom/graph")
            assert reply.status_code == 200, reply.text
            body: dict[str, Any] = reply.json()
            return body

        wait_until(lambda: "out /ada/probe" in graph()["topics"].get("ada", []), "ada's valid /probe bridged")
        shown = graph()
        assert not [t for t in shown["topics"]["ada"] if t.split(" ")[1].startswith("/adam")], shown
        assert shown["names_refused"].get("ada", 0) >= 2, shown
        # What reaches the instructor as adam's GPS is adam's: ada's spoofed samples never do.
        heard_adam, heard_probe = Heard(), Heard()
        instructor.declare_subscriber(gps_key(0, "/adam"), heard_adam)
        instructor.declare_subscriber(data_key(0, "/ada/probe", *POSE), heard_probe)
        spoofed = student.declare_publisher(data_key(domain, "m/uav/sensors/gps", *POSE))
        probe = student.declare_publisher(data_key(domain, "/probe", *POSE))
        seq = 0

        def probe_heard() -> bool:
            nonlocal seq
            seq += 1
            spoofed.put(spoof, attachment=Attachment(seq, time.time_ns(), GID).pack())
            probe.put(b"\x00\x01\x00\x00probe", attachment=Attachment(seq, time.time_ns(), GID).pack())
            return heard_probe.count > 0 and heard_adam.count >= 5

        wait_until(probe_heard, "ada's /probe and adam's own GPS reaching the instructor")
        assert spoof not in heard_adam.payloads
        for token in declared:
            token.undeclare()
