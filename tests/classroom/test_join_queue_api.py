"""The class's load and its join queue through the real app (TestClient enters the lifespan) on
a manual clock: the load route is the instructor's only; a join past capacity waits with a ticket,
is admitted when a world is removed or the instructor lets it through, and a name that has a
world is never queued. The load is a fake source (saturated CPU, every world late), so the verdict
follows the worlds in the class without depending on this machine's load."""

from __future__ import annotations

from collections.abc import Iterator

import pytest
from fastapi.testclient import TestClient

from node_runtime.bus import ManualClock
from server.app import create_app
from server.classroom import ClassServer
from server.classroom.capacity import PlaceLoad
from server.classroom.load import CpuLoad
from server.host.settings import ClassroomSettings, JoinQueueSettings, LabSettings, Listening, Settings

CODE = "QUEUE7"


@pytest.fixture
def clock() -> ManualClock:
    return ManualClock(1_000.0)


@pytest.fixture
def client(clock: ManualClock) -> Iterator[TestClient]:
    settings = Settings(
        listen=Listening(allowed_hosts=("testserver",)),
        lab=LabSettings(launch="rocket", launch_args={"start_delay": "3600"}, viewer=False),
        classroom=ClassroomSettings(
            code=CODE, max_worlds=6, join_queue=JoinQueueSettings(size=2, wait_s=120.0)
        ),
    )
    with TestClient(create_app(settings, clock)) as test_client:
        yield test_client


def server(client: TestClient) -> ClassServer:
    return client.app.state.classroom  # type: ignore[attr-defined,no-any-return]


def saturated_when_busy(classroom: ClassServer) -> None:
    """A fake load: the process saturated and every world late, so the class is full from one world."""

    async def source() -> list[PlaceLoad]:
        worlds = len(classroom.worlds)
        return [PlaceLoad("server", worlds, 60, CpuLoad(0.97, 0.5, 2, "m1", 250.0), worlds)]

    classroom.load.source = source


def join(client: TestClient, name: str) -> tuple[int, dict[str, object]]:
    reply = client.post("/api/classroom/join", json={"name": name, "code": CODE})
    client.cookies.clear()
    return reply.status_code, reply.json()


def poll(client: TestClient, ticket: object) -> tuple[int, dict[str, object]]:
    reply = client.get(f"/api/classroom/join/{ticket}")
    client.cookies.clear()
    return reply.status_code, reply.json()


def bearer(token: object) -> dict[str, str]:
    return {"Authorization": f"Bearer {token}"}


def test_the_load_route_is_the_instructors_and_reports_this_process(client: TestClient) -> None:
    status, ada = join(client, "Ada")
    assert status == 201
    instructor = bearer(server(client).instructor_token)
    assert client.get("/api/classroom/load").status_code == 401
    refused = client.get("/api/classroom/load", headers=bearer(ada["token"]))
    assert refused.status_code == 403 and "only the instructor" in refused.json()["detail"]
    reply = client.get("/api/classroom/load", headers=instructor)
    assert reply.status_code == 200, reply.text
    load = reply.json()
    assert load["capacity"] in ("ok", "near", "full") and load["worlds"] == 1
    (here,) = load["places"]
    assert (here["place"], here["worlds"], here["max_worlds"]) == ("server", 1, 6)
    assert here["cpu"]["rss_mb"] > 10 and here["cpu"]["cores"] >= 1  # measured, not faked
    assert load["queue"]["waiting"] == [] and load["queue"]["size"] == 2
    assert (
        "instructor"
        in client.get("/openapi.json").json()["paths"]["/api/classroom/load"]["get"]["description"]
    )


def test_a_join_past_capacity_waits_and_is_admitted_once_a_world_is_removed(client: TestClient) -> None:
    classroom = server(client)
    saturated_when_busy(classroom)
    instructor = bearer(classroom.instructor_token)
    assert join(client, "Ada")[0] == 201  # no world yet: the class has room
    status, bob = join(client, "Bob")
    assert (status, bob["ahead"], bob["why"]) == (202, 0, "the class server is at its capacity")
    status, cy = join(client, "Cy")
    assert (status, cy["ahead"]) == (202, 1)
    status, dee = join(client, "Dee")
    assert status == 503 and "2 joins already wait" in str(dee["detail"])
    assert join(client, "Bob") == (409, {"detail": "the name 'Bob' is taken in this class (world 'bob')"})
    assert join(client, "Ada")[0] == 409  # a name that has a world is answered at once, never queued
    assert set(classroom.worlds) == {"ada"}

    load = client.get("/api/classroom/load", headers=instructor).json()
    assert load["capacity"] == "full" and "1 of 1 worlds are late" in load["reasons"][0]
    assert [w["student"] for w in load["queue"]["waiting"]] == ["Bob", "Cy"]
    assert poll(client, bob["ticket"])[0] == 202  # still full
    assert poll(client, cy["ticket"]) == (202, {**cy, "ahead": 1})

    assert client.delete("/api/classroom/worlds/ada", headers=instructor).status_code == 200
    status, joined = poll(client, bob["ticket"])
    assert status == 201 and joined["world"] == "bob"
    assert client.get("/api/classroom/me", headers=bearer(joined["token"])).json()["world"] == "bob"
    assert poll(client, cy["ticket"])[1]["ahead"] == 0  # first now, but Bob's world fills the class

    assert (
        client.post(
            "/api/classroom/queue/admit", json={"count": 1}, headers=bearer(joined["token"])
        ).status_code
        == 403
    )
    let = client.post("/api/classroom/queue/admit", json={"count": 1}, headers=instructor)
    assert let.status_code == 200 and let.json()["let_through"] == 1
    status, joined = poll(client, cy["ticket"])
    assert status == 201 and joined["world"] == "cy"
    assert set(classroom.worlds) == {"bob", "cy"}
    assert poll(client, cy["ticket"])[0] == 404  # a ticket is used once


def test_a_waiting_join_is_refused_with_retry_after_once_it_waited_too_long(
    client: TestClient, clock: ManualClock
) -> None:
    saturated_when_busy(server(client))
    assert join(client, "Ada")[0] == 201
    status, bob = join(client, "Bob")
    assert status == 202
    for _ in range(4):  # its page polls (here every 25 s, under abandon_s); the class stays full
        clock.advance(25.0)
        assert poll(client, bob["ticket"])[0] == 202
    clock.advance(25.0)
    reply = client.get(f"/api/classroom/join/{bob['ticket']}")
    assert reply.status_code == 503 and int(reply.headers["Retry-After"]) >= 1
    assert "stayed at its capacity for 120 s" in reply.json()["detail"]
    assert set(server(client).worlds) == {"ada"}


def test_a_machine_at_its_world_budget_queues_the_next_join_until_a_world_is_removed(
    clock: ManualClock,
) -> None:
    """The budget through the real app, with the class server's own load as it measures it (this
    machine's cores and boot id, not a fake): one world a core here, so the machine is full after as
    many joins as it has cores, though no world is late and no node runs."""
    settings = Settings(
        listen=Listening(allowed_hosts=("testserver",)),
        lab=LabSettings(launch="rocket", launch_args={"start_delay": "3600"}, viewer=False),
        classroom=ClassroomSettings(code=CODE, max_worlds=200, worlds_per_core=1, local_workers=0),
    )
    with TestClient(create_app(settings, clock)) as client:
        classroom = server(client)
        instructor = bearer(classroom.instructor_token)
        cores = classroom.cpu.cores
        worlds = []
        for i in range(cores):
            status, joined = join(client, f"Student {i}")
            assert status == 201
            worlds.append(joined["world"])
        status, late = join(client, "Late")
        assert (status, late["ahead"]) == (202, 0)
        load = client.get("/api/classroom/load", headers=instructor).json()
        assert (load["capacity"], load["late"], load["room"]) == ("full", 0, 0)
        assert load["reasons"] == [
            "every place with room is on a machine at its world budget "
            f"(1 worlds a core: {cores} worlds on {cores} cores)"
        ]
        (machine,) = load["machines"]
        assert (machine["worlds"], machine["cores"], machine["budget"]) == (cores, cores, cores)
        assert machine["machine"] == classroom.cpu.machine  # this machine, named by its boot id
        assert poll(client, late["ticket"])[0] == 202
        # A world removed gives its place back: the waiting join is admitted.
        assert client.delete(f"/api/classroom/worlds/{worlds[0]}", headers=instructor).status_code == 200
        status, joined = poll(client, late["ticket"])
        assert status == 201 and joined["world"] == "late"
        assert len(classroom.worlds) == cores
