"""The classroom's two roles behind one interface (server/classroom/roles.py): the class server and a
world worker are each a ``Classroom``, and where they differ each answers for itself, with the
statuses, bodies and close codes the API always gave. The refusals are domain exceptions that
api/errors.py alone turns into statuses and close codes."""

from __future__ import annotations

import inspect
from collections.abc import Iterator
from typing import Any

import pytest
from fastapi.testclient import TestClient
from support.ws import refusal

from api.errors import ERROR_STATUS, CloseCode, refusal_close_code, status_for
from node_runtime.bus import ManualClock
from server.app import create_app
from server.classroom import Classroom, ClassroomError, ClassServer, WorldWorker, errors
from server.classroom.workers import worker_api_token, world_call_token
from server.host.settings import (
    ClassroomSettings,
    LabSettings,
    Listening,
    Settings,
    WorkerSettings,
    WorldLimits,
)

CODE = "ROLES1"
CLASS_TOKEN = "the-instructors-token"
LAB = LabSettings(launch="rocket", launch_args={"start_delay": "3600"}, viewer=False)
HOST = {
    "world": "ada",
    "student": "Ada",
    "domain_id": 3,
    "launch": "rocket",
    "launch_args": {"start_delay": "3600"},
}
WORKER_ONLY = "this is a world worker: its class server has the class's load and queue"


# -- the interface -------------------------------------------------------------------------------
def protocol_members() -> set[str]:
    return {
        name
        for name, _ in inspect.getmembers(Classroom)
        if not name.startswith("_") and name not in dir(object)
    } | set(Classroom.__annotations__)


@pytest.mark.parametrize("role", [ClassServer, WorldWorker])
def test_both_roles_have_every_member_of_the_classroom_protocol(role: type) -> None:
    """mypy checks the signatures (server/classroom/roles.py); here, that each role has every member,
    methods as methods (coroutines where the Protocol's are) and properties as properties or attributes."""
    members = protocol_members()
    assert {"grant", "world_for", "charge_write", "join", "host", "kick", "class_load", "workers"} <= members
    settings = worker_settings() if role is WorldWorker else class_settings()
    instance = role(settings, ManualClock(0.0))
    for name in members:
        assert hasattr(instance, name), (role.__name__, name)
        declared = inspect.getattr_static(Classroom, name, None)
        if inspect.isfunction(declared):
            own = inspect.getattr_static(role, name)
            assert inspect.iscoroutinefunction(own) == inspect.iscoroutinefunction(declared), (role, name)


# -- the refusals and their one table ------------------------------------------------------------
def refusal_kinds() -> list[type[ClassroomError]]:
    return [
        kind
        for _, kind in inspect.getmembers(errors, inspect.isclass)
        if issubclass(kind, ClassroomError) and kind is not ClassroomError
    ]


def test_every_classroom_refusal_has_one_row_in_the_error_table_and_carries_no_status() -> None:
    kinds = refusal_kinds()
    assert len(kinds) >= 20
    rows = [kind for kind, _ in ERROR_STATUS if issubclass(kind, ClassroomError)]
    assert sorted(rows, key=lambda k: k.__name__) == sorted(kinds, key=lambda k: k.__name__)
    for kind in kinds:
        exc = kind("why") if kind is not errors.WorkerRefusedError else kind("why", 409)
        assert not hasattr(exc, "status"), kind.__name__
        assert status_for(exc) is not None, kind.__name__


@pytest.mark.parametrize(
    ("exc", "status", "close"),
    [
        (errors.NotAuthenticatedError("x"), 401, CloseCode.UNAUTHORIZED),
        (errors.NotYoursError("x"), 403, CloseCode.FORBIDDEN),
        (errors.WorldNotNamedError("x"), 400, CloseCode.POLICY_VIOLATION),
        (errors.UnknownWorldError("x"), 404, CloseCode.POLICY_VIOLATION),
        (errors.WorldElsewhereError("x"), 404, CloseCode.POLICY_VIOLATION),
        (errors.RateLimitedError("x", 2.0), 429, CloseCode.POLICY_VIOLATION),
    ],
)
def test_a_refusal_at_a_sockets_door_closes_with_its_own_code_else_a_policy_violation(
    exc: ClassroomError, status: int, close: CloseCode
) -> None:
    assert (status_for(exc), refusal_close_code(exc)) == (status, close)


def test_a_world_workers_own_refusal_is_passed_on_and_its_failure_is_a_bad_gateway() -> None:
    assert status_for(errors.WorkerRefusedError("world worker 'w1': gone", 404)) == 404
    assert status_for(errors.WorkerRefusedError("world worker 'w1': busy", 429)) == 429
    assert status_for(errors.WorkerRefusedError("world worker 'w1': broke", 500)) == 502
    assert status_for(errors.WorkerFailedError("world worker 'w1' did not answer")) == 502
    assert status_for(errors.WorkerTimeoutError("world worker 'w1' did not answer within 5 s")) == 504


# -- a world worker, through the app -------------------------------------------------------------
def worker_settings() -> Settings:
    return Settings(
        listen=Listening(allowed_hosts=("testserver",)),
        lab=LAB,
        classroom=ClassroomSettings(max_worlds=2, world=WorldLimits(writes_hz=1.0, writes_burst=2)),
        worker=WorkerSettings(id="wm", url="http://127.0.0.1:1", class_token=CLASS_TOKEN),
    )


def class_settings() -> Settings:
    return Settings(
        listen=Listening(allowed_hosts=("testserver",)),
        lab=LAB,
        classroom=ClassroomSettings(
            code=CODE, max_worlds=2, world=WorldLimits(writes_hz=1.0, writes_burst=2)
        ),
    )


@pytest.fixture
def worker() -> Iterator[TestClient]:
    with TestClient(create_app(worker_settings(), ManualClock(1_000.0))) as client:
        yield client


@pytest.fixture
def server() -> Iterator[TestClient]:
    with TestClient(create_app(class_settings(), ManualClock(1_000.0))) as client:
        yield client


AS_CLASS_SERVER = {"Authorization": f"Bearer {worker_api_token(CLASS_TOKEN, 'wm')}"}


def detail(reply: Any) -> tuple[int, Any]:
    return reply.status_code, reply.json()["detail"]


def test_a_world_worker_takes_no_join_and_keeps_no_load_queue_or_saved_students(worker: TestClient) -> None:
    joined = worker.post("/api/classroom/join", json={"name": "Ada", "code": CODE})
    assert detail(joined) == (403, "this is a world worker: students join through the class server")
    assert detail(worker.get("/api/classroom/load", headers=AS_CLASS_SERVER)) == (404, WORKER_ONLY)
    assert detail(worker.get("/api/classroom/join/some-ticket")) == (404, WORKER_ONLY)
    admit = worker.post("/api/classroom/queue/admit", json={"count": 1}, headers=AS_CLASS_SERVER)
    assert detail(admit) == (404, WORKER_ONLY)
    released = worker.post("/api/classroom/checkpoints/ada/release", headers=AS_CLASS_SERVER)
    assert detail(released) == (404, "only a class server keeps whose progress is whose")
    graph = worker.get("/api/classroom/graph", headers=AS_CLASS_SERVER)
    assert detail(graph) == (404, "this class server has no Zenoh graph of its own")
    places = worker.get("/api/classroom/workers", headers=AS_CLASS_SERVER)
    assert places.status_code == 200, places.text
    body = places.json()
    assert (body["workers"], body["started_here"], body["spread"]) == ([], [], None)
    assert body["local"]["worlds"] == 0 and body["local"]["max_worlds"] == 2


def test_a_world_worker_hosts_checks_the_handed_progress_first_and_kicks_as_told(worker: TestClient) -> None:
    bad = worker.post("/api/classroom/host", json={**HOST, "progress": {"nope": 1}}, headers=AS_CLASS_SERVER)
    assert bad.status_code == 422 and bad.json()["detail"].startswith(
        "the progress handed over with world 'ada' is not one: "
    )
    hosted = worker.post("/api/classroom/host", json=HOST, headers=AS_CLASS_SERVER)
    assert hosted.status_code == 201, hosted.text
    again = worker.post("/api/classroom/host", json=HOST, headers=AS_CLASS_SERVER)
    assert detail(again) == (409, "world 'ada' is already here")
    # Its checkpoint table and reports: its own worlds, nothing of saved students or other workers.
    table = worker.get("/api/classroom/checkpoints", headers=AS_CLASS_SERVER)
    assert table.status_code == 200 and [r["world"] for r in table.json()["students"]] == ["ada"]
    assert "worker_errors" not in table.json()
    sent = worker.post(
        "/api/classroom/broadcast",
        json={"topic": "/abort_takeoff", "msg": {"data": True}},
        headers=AS_CLASS_SERVER,
    )
    assert sent.status_code == 200 and sent.json() == {"reached": ["ada"], "refused": {}}
    # A student's calls come through the class server, which charged them: more writes than the
    # world's burst are not refused here.
    student = {"Authorization": f"Bearer {world_call_token(CLASS_TOKEN, 'wm', 'ada')}", "X-Lab-World": "ada"}
    for _ in range(5):
        reply = worker.post(
            "/api/publish", json={"topic": "/abort_takeoff", "msg": {"data": True}}, headers=student
        )
        assert reply.status_code == 200, reply.text
    kicked = worker.delete("/api/classroom/worlds/ada?workspace=remove", headers=AS_CLASS_SERVER)
    assert kicked.status_code == 200 and kicked.json() == {"kicked": "ada", "student": "Ada"}
    assert detail(worker.delete("/api/classroom/worlds/ada", headers=AS_CLASS_SERVER)) == (
        404,
        "no world named 'ada'",
    )


# -- the class server, through the app -----------------------------------------------------------
def test_a_class_server_hosts_no_world_for_another_and_charges_a_students_writes(server: TestClient) -> None:
    classroom: ClassServer = server.app.state.classroom  # type: ignore[attr-defined]
    instructor = {"Authorization": f"Bearer {classroom.instructor_token}"}
    bad = {**HOST, "progress": {"nope": 1}}  # refused for what it is first: the role, not the body
    assert detail(server.post("/api/classroom/host", json=bad, headers=instructor)) == (
        404,
        "only a world worker hosts worlds for a class server",
    )
    token = server.post("/api/classroom/join", json={"name": "Ada", "code": CODE}).json()["token"]
    server.cookies.clear()
    ada = {"Authorization": f"Bearer {token}"}
    publish = {"topic": "/abort_takeoff", "msg": {"data": True}}
    codes = [server.post("/api/publish", json=publish, headers=ada).status_code for _ in range(3)]
    assert codes == [200, 200, 429]
    refused = server.post("/api/publish", json=publish, headers=ada)
    assert refused.headers["Retry-After"] == "1"
    assert refused.json() == {"detail": "too many requests for world 'ada': at most 1 writes a second"}
    # The instructor's writes are not charged.
    named = {**instructor, "X-Lab-World": "ada"}
    assert [server.post("/api/publish", json=publish, headers=named).status_code for _ in range(3)] == [
        200
    ] * 3


def test_a_class_servers_socket_refusals_keep_their_close_codes(server: TestClient) -> None:
    classroom: ClassServer = server.app.state.classroom  # type: ignore[attr-defined]
    token = server.post("/api/classroom/join", json={"name": "Ada", "code": CODE}).json()["token"]
    server.cookies.clear()
    instructor = classroom.instructor_token
    assert refusal(server, "/ws/keys").code == CloseCode.UNAUTHORIZED
    unnamed = refusal(server, f"/ws/keys?token={instructor}")
    assert (unnamed.code, unnamed.reason) == (
        CloseCode.POLICY_VIOLATION,
        "name a world (the X-Lab-World header or ?world=)",
    )
    nobody = refusal(server, f"/ws/keys?token={instructor}&world=nobody")
    assert (nobody.code, nobody.reason) == (CloseCode.POLICY_VIOLATION, "no world named 'nobody'")
    other = refusal(server, f"/ws/keys?token={token}&world=bob")
    assert (other.code, other.reason) == (CloseCode.FORBIDDEN, "your token is for world 'ada', not 'bob'")
