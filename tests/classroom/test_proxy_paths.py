"""The class server's proxy to its world workers forwards exactly what it authorised.

A path is checked as sent: one that a normaliser would change (``./``, ``x/../``, ``%2e``,
``%2f``, ``//``, a backslash) is refused with a 400 before anything reads it, on every route, so
no hop behind the class server can turn a student's world call into an instructor's route. And a
worker trusts a student's forwarded call for that student's world only: the class server forwards
it with a credential for that one world, never with the instructor's.

A class server that hosts no world itself and one world worker run as processes of their own on
loopback (ended by their ids). Requests go out through ``http.client`` and a raw socket, which
send the path byte for byte.
"""

from __future__ import annotations

import http.client
import json
import socket
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any
from urllib.parse import urlsplit

import pytest
from support.app import App, WorldWorker, instructor_token, wait_for_workers
from support.http import HTTP

from server.classroom.workers import worker_api_token, world_call_token

CODE = "PRX042"
WORKER = "wp"
FLY_TARGET = {"x": 0.0, "y": 0.0, "z": 2.0}
GPS = "/ws/topics/uav/sensors/gps"
READ_S = 15.0
# Spellings of one path that a normaliser (httpx's, a reverse proxy's, a browser's) would change.
NOT_CANONICAL = (
    "/api/./classroom/worlds",
    "/api/x/../classroom/worlds",
    "/api/%2e/classroom/worlds",
    "/api/%2E%2e/api/classroom/worlds",
    "/api%2fclassroom/worlds",
    "/api//classroom/worlds",
    "/api/.%2Fclassroom/worlds",
    "/api\\classroom/worlds",
    "/api/%5cclassroom/worlds",
    "/api/classroom/worlds/.",
)


@dataclass
class Class:
    app: App
    worker: WorldWorker
    worker_url: str
    instructor: str
    tokens: dict[str, str]  # world → its student's token

    @property
    def address(self) -> tuple[str, int]:
        parts = urlsplit(self.app.url)
        assert parts.hostname is not None and parts.port is not None
        return parts.hostname, parts.port

    def raw(self, method: str, path: str, token: str | None, body: Any = None, **headers: str) -> Reply:
        return raw_http(self.address, method, path, token, body, headers)

    def worker_call(self, method: str, path: str, token: str, body: Any = None, **headers: str) -> Reply:
        parts = urlsplit(self.worker_url)
        assert parts.hostname is not None and parts.port is not None
        return raw_http((parts.hostname, parts.port), method, path, token, body, headers)

    def worker_worlds(self) -> dict[str, dict[str, Any]]:
        """The worlds the worker hosts, as it reports them to its class server."""
        reply = self.worker_call("GET", "/api/classroom/worlds", worker_api_token(self.instructor, WORKER))
        assert reply.status == 200, reply.text
        return {w["world"]: w for w in reply.json()["worlds"]}

    def published(self, world: str, topic: str) -> int:
        reply = self.raw("GET", f"/api/topics/{topic.lstrip('/')}", self.tokens[world])
        assert reply.status == 200, reply.text
        return int(reply.json()["publish_count"])


@dataclass
class Reply:
    status: int
    text: str

    def json(self) -> Any:
        return json.loads(self.text)


def raw_http(
    address: tuple[str, int], method: str, path: str, token: str | None, body: Any, headers: dict[str, str]
) -> Reply:
    """One request with ``path`` sent exactly as given (http.client does not normalise it)."""
    connection = http.client.HTTPConnection(*address, timeout=30)
    sent = dict(headers)
    if token is not None:
        sent["Authorization"] = f"Bearer {token}"
    data = None
    if body is not None:
        data = json.dumps(body).encode()
        sent["Content-Type"] = "application/json"
    try:
        connection.request(method, path, body=data, headers=sent)
        response = connection.getresponse()
        return Reply(response.status, response.read().decode(errors="replace"))
    finally:
        connection.close()


def raw_ws_open(address: tuple[str, int], path: str, headers: dict[str, str]) -> tuple[int, bytes]:
    """A WebSocket handshake for ``path`` as given: the status the server answers, and the first
    bytes after the head (a text frame, once it is open)."""
    lines = [
        f"GET {path} HTTP/1.1",
        f"Host: {address[0]}:{address[1]}",
        "Upgrade: websocket",
        "Connection: Upgrade",
        "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==",
        "Sec-WebSocket-Version: 13",
        *(f"{k}: {v}" for k, v in headers.items()),
    ]
    with socket.create_connection(address, timeout=READ_S) as sock:
        sock.sendall(("\r\n".join(lines) + "\r\n\r\n").encode("latin-1"))
        data = b""
        while b"\r\n\r\n" not in data:
            chunk = sock.recv(4096)
            if not chunk:
                break
            data += chunk
        head, _, rest = data.partition(b"\r\n\r\n")
        status = int(head.split(b" ", 2)[1])
        if status == 101 and not rest:
            rest = sock.recv(4096)  # the first frame the socket carries
        return status, rest


def ws_refused(status: int, rest: bytes) -> bool:
    """Whether a handshake was refused: with an HTTP status, or opened only to close at once with
    4403 (another world) or 4401 (no valid token)."""
    if status != 101:
        return 400 <= status < 500
    return len(rest) >= 4 and rest[0] == 0x88 and int.from_bytes(rest[2:4], "big") in (4401, 4403)


@pytest.fixture(scope="module")
def klass(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Class]:
    root = tmp_path_factory.mktemp("proxy_paths")
    app = App(
        root, "--classroom", "--class-code", CODE, "--launch", "fly", "--local-worlds", "0", "--no-foxglove"
    )
    worker: WorldWorker | None = None
    try:
        instructor = instructor_token(app.log_tail(10**6))
        worker = WorldWorker(root, app.router, instructor, WORKER, "--max-worlds", "4")
        listed = wait_for_workers(app.url, instructor, {WORKER})
        tokens: dict[str, str] = {}
        for name in ("Ada", "Bob"):
            reply = HTTP.post(f"{app.url}/api/classroom/join", json={"name": name, "code": CODE}, timeout=60)
            assert reply.status_code == 201, reply.text
            tokens[reply.json()["world"]] = reply.json()["token"]
        yield Class(app, worker, listed[0]["url"], instructor, tokens)
    finally:
        if worker is not None:
            worker.stop()
        app.stop()


@pytest.mark.parametrize("path", NOT_CANONICAL)
def test_a_path_that_normalisation_would_change_is_refused_400(klass: Class, path: str) -> None:
    for token in (klass.tokens["ada"], klass.instructor):
        reply = klass.raw("GET", path, token)
        assert reply.status == 400, (path, reply.status, reply.text)
        assert "path" in reply.json()["detail"], reply.text
    # The same call spelt plainly is the instructor's, and works.
    assert klass.raw("GET", "/api/classroom/worlds", klass.instructor).status == 200
    assert klass.raw("GET", "/api/classroom/worlds", klass.tokens["ada"]).status == 403


def test_a_student_cannot_list_the_workers_worlds(klass: Class) -> None:
    reply = klass.raw("GET", "/api/./classroom/worlds", klass.tokens["ada"])
    assert reply.status == 400, reply.text
    assert "dot segment" in reply.json()["detail"]
    listed = klass.raw("GET", "/api/classroom/worlds", klass.instructor)
    assert listed.status == 200 and {w["world"] for w in listed.json()["worlds"]} >= {"ada", "bob"}


def test_a_student_cannot_reset_another_world(klass: Class) -> None:
    before = klass.worker_worlds()["bob"]["resets"]
    reply = klass.raw("POST", "/api/./classroom/worlds/bob/reset", klass.tokens["ada"])
    assert reply.status == 400, reply.text
    assert klass.worker_worlds()["bob"]["resets"] == before  # bob's rocket was not reset
    # The instructor's own reset of bob's world works, through the class server.
    reset = klass.raw("POST", "/api/classroom/worlds/bob/reset", klass.instructor)
    assert reset.status == 200, reset.text
    assert klass.worker_worlds()["bob"]["resets"] == before + 1


def test_a_student_cannot_remove_another_world(klass: Class) -> None:
    reply = klass.raw("DELETE", "/api/./classroom/worlds/bob", klass.tokens["ada"])
    assert reply.status == 400, reply.text
    assert "bob" in klass.worker_worlds()  # still there, on the worker and in the class
    assert klass.raw("GET", "/api/topics", klass.tokens["bob"]).status == 200
    # The instructor removes a world of a student who joined for it.
    joined = HTTP.post(f"{klass.app.url}/api/classroom/join", json={"name": "Cy", "code": CODE}, timeout=60)
    assert joined.status_code == 201, joined.text
    assert "cy" in klass.worker_worlds()
    removed = klass.raw("DELETE", "/api/classroom/worlds/cy", klass.instructor)
    assert removed.status == 200, removed.text
    assert "cy" not in klass.worker_worlds()


def test_a_student_cannot_host_a_world_on_the_worker(klass: Class) -> None:
    before = set(klass.worker_worlds())
    body = {
        "world": "eve",
        "student": "Eve",
        "domain_id": 150,
        "launch": "rocket",
        "launch_args": {"start_delay": "3600"},
    }
    reply = klass.raw("POST", "/api/./classroom/host", klass.tokens["ada"], body)
    assert reply.status == 400, reply.text
    assert set(klass.worker_worlds()) == before  # no world was made
    # A world is hosted there when the class server asks, for a student who joins.
    joined = HTTP.post(f"{klass.app.url}/api/classroom/join", json={"name": "Dee", "code": CODE}, timeout=60)
    assert joined.status_code == 201, joined.text
    assert set(klass.worker_worlds()) == before | {"dee"}


def test_a_student_cannot_broadcast_to_every_drone(klass: Class) -> None:
    topic = "/uav/input/position"
    before = {world: klass.published(world, topic) for world in ("ada", "bob")}
    body = {"topic": topic, "msg": FLY_TARGET}
    reply = klass.raw("POST", "/api/./classroom/broadcast", klass.tokens["ada"], body)
    assert reply.status == 400, reply.text
    assert {world: klass.published(world, topic) for world in ("ada", "bob")} == before  # no drone moved
    # The instructor's broadcast reaches both worlds on the worker.
    sent = klass.raw("POST", "/api/classroom/broadcast", klass.instructor, body)
    assert sent.status == 200, sent.text
    assert set(sent.json()["reached"]) >= {"ada", "bob"}
    assert all(klass.published(world, topic) == before[world] + 1 for world in ("ada", "bob"))


def test_a_students_own_world_calls_are_still_proxied(klass: Class) -> None:
    ada = klass.tokens["ada"]
    assert klass.raw("GET", "/api/topics", ada).status == 200
    before = klass.published("ada", "/uav/input/position")
    reply = klass.raw("POST", "/api/publish", ada, {"topic": "/uav/input/position", "msg": FLY_TARGET})
    assert reply.status == 200, reply.text
    assert klass.published("ada", "/uav/input/position") == before + 1
    assert klass.raw("GET", "/page/views", ada).status == 200
    # Her socket to her world's GPS opens through the proxy and carries its frames.
    status, frame = raw_ws_open(klass.address, GPS, {"Authorization": f"Bearer {ada}"})
    assert status == 101 and b"/uav/sensors/gps" in frame, (status, frame[:200])


@pytest.mark.parametrize("path", [f"/ws/./{GPS[4:]}", "/class/./rosbridge", "/ws/x/../keys", "/%2e/"])
def test_a_websocket_whose_path_normalisation_would_change_is_refused(klass: Class, path: str) -> None:
    status, body = raw_ws_open(klass.address, path, {"Authorization": f"Bearer {klass.tokens['ada']}"})
    assert status == 400, (path, status, body[:200])
    assert b"path" in body


def test_the_worker_takes_a_world_credential_for_its_own_world_only(klass: Class) -> None:
    for_ada = world_call_token(klass.instructor, WORKER, "ada")
    # Naming ada: her world answers, as it does to her calls through the class server.
    assert klass.worker_call("GET", "/api/topics", for_ada, **{"X-Lab-World": "ada"}).status == 200
    # Naming bob, or no world: refused, and nothing of bob's world is read or changed.
    other = klass.worker_call("GET", "/api/topics", for_ada, **{"X-Lab-World": "bob"})
    assert other.status == 403, other.text
    assert "'ada'" in other.json()["detail"]
    before = klass.published("bob", "/uav/input/position")
    body = {"topic": "/uav/input/position", "msg": FLY_TARGET}
    assert klass.worker_call("POST", "/api/publish", for_ada, body, **{"X-Lab-World": "bob"}).status == 403
    assert klass.published("bob", "/uav/input/position") == before
    # Nor does it reach the worker's own routes, which only the class server calls: what a
    # normalised path used to reach there with the instructor's token, it cannot.
    resets_before = {name: world["resets"] for name, world in klass.worker_worlds().items()}
    host = {"world": "eve", "student": "Eve", "domain_id": 150, "launch": "rocket"}
    for method, path, payload in (
        ("GET", "/api/classroom/worlds", None),
        ("POST", "/api/classroom/worlds/bob/reset", None),
        ("DELETE", "/api/classroom/worlds/bob", None),
        ("POST", "/api/classroom/host", host),
        ("POST", "/api/classroom/broadcast", body),
    ):
        reply = klass.worker_call(method, path, for_ada, payload, **{"X-Lab-World": "ada"})
        assert reply.status == 403, (method, path, reply.text)
    assert {name: world["resets"] for name, world in klass.worker_worlds().items()} == resets_before
    assert klass.published("bob", "/uav/input/position") == before
    worker_address = urlsplit(klass.worker_url)
    assert worker_address.hostname is not None and worker_address.port is not None
    status, rest = raw_ws_open(
        (worker_address.hostname, worker_address.port),
        GPS + "?world=bob",
        {"Authorization": f"Bearer {for_ada}"},
    )
    assert ws_refused(status, rest), (status, rest[:200])
    status, frame = raw_ws_open(
        (worker_address.hostname, worker_address.port),
        GPS,
        {"Authorization": f"Bearer {for_ada}", "X-Lab-World": "ada"},
    )
    assert status == 101 and b"/uav/sensors/gps" in frame
    # A credential for a world on another worker's id, or a made-up one, opens nothing here.
    forged = world_call_token(klass.instructor, "another-worker", "ada")
    assert klass.worker_call("GET", "/api/topics", forged, **{"X-Lab-World": "ada"}).status == 401
    assert (
        klass.worker_call("GET", "/api/topics", "world:ada:" + "0" * 64, **{"X-Lab-World": "ada"}).status
        == 401
    )


def test_the_console_logs_a_refused_path_once_without_the_token(klass: Class) -> None:
    marker = "/api/./classroom/worlds/marker-path"
    assert klass.raw("GET", marker, klass.tokens["bob"]).status == 400
    lines = [line for line in klass.app.log_tail(10**6).splitlines() if "marker-path" in line]
    assert len(lines) == 1, lines
    assert "WARNING" in lines[0] and klass.tokens["bob"] not in lines[0]
    assert klass.tokens["bob"].split(".")[1] not in klass.app.log_tail(10**6)
