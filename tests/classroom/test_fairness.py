"""One student's load stays in their world: launches, resets and WebSockets are capped per world
(through the real app, on a manual clock), each refusal names its limit and changes nothing, and
the same use under the cap, another student's and the instructor's still work."""

from __future__ import annotations

import asyncio
import json
from collections.abc import Iterator
from contextlib import ExitStack
from typing import Any

import pytest
from fastapi.testclient import TestClient
from support.ws import receive_within

from api.errors import CloseCode
from node_runtime.bus import ManualClock
from server.app import create_app
from server.classroom import ClassServer
from server.host.settings import ClassroomSettings, LabSettings, Listening, Settings, WorldLimits

CODE = "FAIR42"
SOCKETS = 3
LAUNCHES = 2
RESETS = 2
RESET_PERIOD_S = 10.0
WRITES = 6
RUN = {"package": "rocketship", "executable": "countdown"}


@pytest.fixture
def clock() -> ManualClock:
    return ManualClock(1_000.0)


def class_app(clock: ManualClock, **world: Any) -> TestClient:
    """A class of three rocket worlds; ``world`` overrides their WorldLimits."""
    limits: dict[str, Any] = {
        "writes_hz": 1.0,
        "writes_burst": WRITES,
        "launches": LAUNCHES,
        "resets_hz": 1 / RESET_PERIOD_S,
        "resets_burst": RESETS,
        "sockets": SOCKETS,
    }
    settings = Settings(
        listen=Listening(allowed_hosts=("testserver",)),
        lab=LabSettings(launch="rocket", launch_args={"start_delay": "3600"}, viewer=False),
        classroom=ClassroomSettings(code=CODE, max_worlds=3, world=WorldLimits(**{**limits, **world})),
    )
    return TestClient(create_app(settings, clock))


@pytest.fixture
def client(clock: ManualClock) -> Iterator[TestClient]:
    with class_app(clock) as test_client:
        yield test_client


def classroom(client: TestClient) -> ClassServer:
    return client.app.state.classroom  # type: ignore[attr-defined,no-any-return]


def join(client: TestClient, name: str) -> dict[str, str]:
    reply = client.post("/api/classroom/join", json={"name": name, "code": CODE})
    assert reply.status_code == 201, reply.text
    client.cookies.clear()
    return {"Authorization": f"Bearer {reply.json()['token']}"}


def instructor(client: TestClient, world: str) -> dict[str, str]:
    return {"Authorization": f"Bearer {classroom(client).instructor_token}", "X-Lab-World": world}


def node_names(client: TestClient, world: str) -> set[str]:
    lab = classroom(client).worlds[world].lab
    assert lab is not None
    return {n.fully_qualified_name for n in lab.bus.nodes}


# -- launches and runs -----------------------------------------------------------------------------
def test_launches_past_the_worlds_cap_are_429_and_start_nothing(client: TestClient) -> None:
    ada, bob = join(client, "Ada"), join(client, "Bob")
    for i in range(LAUNCHES):
        started = client.post("/api/run", json={**RUN, "name": f"count{i}"}, headers=ada)
        assert started.status_code == 201, started.text
    before = node_names(client, "ada")

    refused_run = client.post("/api/run", json={**RUN, "name": "one_too_many"}, headers=ada)
    refused_launch = client.post(
        "/api/launch", json={"package": "rocketship", "file": "rocket.launch"}, headers=ada
    )

    assert (refused_run.status_code, refused_launch.status_code) == (429, 429)
    assert f"at most {LAUNCHES} launches and runs" in refused_run.json()["detail"]
    assert node_names(client, "ada") == before
    # Another world has its own allowance, and stopping one of Ada's frees hers.
    assert client.post("/api/run", json={**RUN, "name": "bobs"}, headers=bob).status_code == 201
    first = client.get("/api/launches", headers=ada).json()[0]["id"]
    assert client.delete(f"/api/launches/{first}", headers=ada).status_code == 200
    assert client.post("/api/run", json={**RUN, "name": "again"}, headers=ada).status_code == 201


def test_a_launch_with_more_nodes_than_a_world_takes_is_429(clock: ManualClock) -> None:
    with class_app(clock, launch_nodes=2) as client:
        ada = join(client, "Ada")
        before = node_names(client, "ada")
        refused = client.post(
            "/api/launch", json={"package": "rocketship", "file": "rocket.launch"}, headers=ada
        )
        assert refused.status_code == 429 and "at most 2 nodes in one launch" in refused.json()["detail"]
        assert node_names(client, "ada") == before
        assert client.post("/api/run", json={**RUN, "name": "one"}, headers=ada).status_code == 201


# -- resets ----------------------------------------------------------------------------------------
def reset(client: TestClient, headers: dict[str, str], world: str = "ada") -> Any:
    return client.post(f"/api/classroom/worlds/{world}/reset", headers=headers)


def test_a_reset_loop_is_429_with_retry_after_and_resets_nothing(
    client: TestClient, clock: ManualClock
) -> None:
    ada = join(client, "Ada")
    for _ in range(RESETS):
        assert reset(client, ada).status_code == 200
    world = classroom(client).worlds["ada"]
    lab = world.lab

    refused = reset(client, ada)

    assert refused.status_code == 429
    assert f"too many resets of world 'ada': at most {RESETS} in a row" in refused.json()["detail"]
    assert 1 <= int(refused.headers["Retry-After"]) <= RESET_PERIOD_S
    assert (world.resets, world.lab) == (RESETS, lab)  # the same lab: not started over
    # The instructor's resets are not the student's; and the student's come back with time.
    assert reset(client, instructor(client, "ada")).status_code == 200
    clock.advance(float(refused.headers["Retry-After"]))
    assert reset(client, ada).status_code == 200
    assert world.resets == RESETS + 2


def test_a_reset_is_one_of_the_worlds_writes(client: TestClient) -> None:
    ada = join(client, "Ada")
    for _ in range(WRITES):
        published = client.post("/api/publish", json={"topic": "/countdown", "msg": {"data": 3}}, headers=ada)
        assert published.status_code == 200, published.text
    world = classroom(client).worlds["ada"]

    refused = reset(client, ada)

    assert refused.status_code == 429 and "writes a second" in refused.json()["detail"]
    assert "Retry-After" in refused.headers
    assert world.resets == 0
    assert world.reset_limit is not None and world.reset_limit.ready()  # not charged a reset either


# -- WebSockets ------------------------------------------------------------------------------------
ROUTES = ["/ws/keys", "/ws/topics/countdown", "/rosbridge"]


@pytest.mark.parametrize("route", ROUTES)
def test_a_socket_past_the_worlds_cap_is_closed_1013_and_opens_nothing(
    client: TestClient, route: str
) -> None:
    ada, bob = join(client, "Ada"), join(client, "Bob")
    world = classroom(client).worlds["ada"]
    with ExitStack() as open_sockets:
        for _ in range(SOCKETS):
            open_sockets.enter_context(client.websocket_connect("/ws/keys", headers=ada))
        before = node_names(client, "ada")
        with client.websocket_connect(route, headers=ada) as refused:
            closed = receive_within(refused)
        assert closed["type"] == "websocket.close" and closed["code"] == CloseCode.TRY_AGAIN_LATER
        assert f"at most {SOCKETS} WebSockets open for world 'ada'" in closed["reason"]
        assert world.sockets == SOCKETS and node_names(client, "ada") == before
        # Bob's sockets are his own, and the instructor's are not capped.
        with (
            client.websocket_connect(route, headers=bob),
            client.websocket_connect(route, headers=instructor(client, "ada")),
        ):
            assert classroom(client).worlds["bob"].sockets == 1
    assert world.sockets == 0  # each closed socket gave its place back
    with client.websocket_connect("/ws/topics/countdown", headers=ada) as echo:
        assert (
            client.post(
                "/api/publish", json={"topic": "/countdown", "msg": {"data": 7}}, headers=ada
            ).status_code
            == 200
        )
        assert json.loads(receive_within(echo)["text"])["msg"] == {"data": 7}


# -- what a world's sockets send and take ------------------------------------------------------------
FRAMES_HZ = 5


def echo_outbox(client: TestClient, world: str) -> int:
    lab = classroom(client).worlds[world].lab
    assert lab is not None and client.portal is not None
    return int(client.portal.call(lambda: sum(len(n.outbox) for n in lab.bus.nodes if hasattr(n, "outbox"))))


def test_a_worlds_sockets_send_within_its_frame_budget_and_the_rest_waits(clock: ManualClock) -> None:
    with class_app(clock, socket_frames_hz=FRAMES_HZ, writes_burst=50) as client:
        ada = join(client, "Ada")
        with client.websocket_connect("/ws/topics/countdown?queue_length=50", headers=ada) as echo:
            for i in range(2 * FRAMES_HZ):
                reply = client.post(
                    "/api/publish", json={"topic": "/countdown", "msg": {"data": i}}, headers=ada
                )
                assert reply.status_code == 200
            first = [json.loads(receive_within(echo)["text"])["msg"]["data"] for _ in range(FRAMES_HZ)]
            assert first == list(range(FRAMES_HZ))
            # The budget is spent: the rest waits in the socket's own queue, none of it sent.
            assert echo_outbox(client, "ada") == FRAMES_HZ
            clock.advance(1.0)
            rest = [json.loads(receive_within(echo)["text"])["msg"]["data"] for _ in range(FRAMES_HZ)]
            assert rest == list(range(FRAMES_HZ, 2 * FRAMES_HZ))


def test_a_worlds_rosbridge_requests_wait_for_its_budget_and_none_is_lost(clock: ManualClock) -> None:
    with class_app(clock, socket_requests_hz=2) as client:
        ada = join(client, "Ada")
        lab = classroom(client).worlds["ada"].lab
        assert lab is not None and lab.socket_requests is not None and client.portal is not None

        def latest() -> int | None:
            topic = lab.bus.topics.get("/countdown")
            return None if topic is None or topic.latest is None else int(topic.latest.data)

        def wait_for(value: int) -> None:
            for _ in range(200):
                if client.portal.call(latest) == value:  # type: ignore[union-attr]
                    return
                client.portal.call(asyncio.sleep, 0.01)  # type: ignore[union-attr]
            pytest.fail(f"/countdown never reached {value}")

        with client.websocket_connect("/rosbridge", headers=ada) as bridge:
            for i in range(1, 5):
                bridge.send_json({"op": "publish", "topic": "/countdown", "msg": {"data": i}})
            wait_for(2)
            assert not lab.socket_requests.ready()  # two taken, two waiting in the socket
            clock.advance(1.0)
            wait_for(4)


def test_a_worlds_rosbridge_sockets_spend_the_same_frame_budget(clock: ManualClock) -> None:
    with class_app(clock, socket_frames_hz=FRAMES_HZ, writes_burst=50) as client:
        ada = join(client, "Ada")
        lab = classroom(client).worlds["ada"].lab
        assert lab is not None and lab.socket_frames is not None
        with client.websocket_connect("/rosbridge", headers=ada) as bridge:
            bridge.send_json({"op": "subscribe", "topic": "/countdown", "queue_length": 50})
            for i in range(2 * FRAMES_HZ):
                reply = client.post(
                    "/api/publish", json={"topic": "/countdown", "msg": {"data": i}}, headers=ada
                )
                assert reply.status_code == 200

            def frames() -> list[int]:
                return [json.loads(receive_within(bridge)["text"])["msg"]["data"] for _ in range(FRAMES_HZ)]

            assert frames() == list(range(FRAMES_HZ))
            assert not lab.socket_frames.ready()  # spent by this socket: the rest waits for time
            clock.advance(1.0)
            assert frames() == list(range(FRAMES_HZ, 2 * FRAMES_HZ))
