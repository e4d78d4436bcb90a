"""A class server through the real app: worlds per student, tokens that scope every call, the
instructor's controls. The worlds run on one manual clock that the tests step."""

from __future__ import annotations

import json
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient
from support.ws import receive_within, refusal

from api.errors import CloseCode
from node_runtime.bus import ManualClock
from server.app import create_app
from server.classroom import ClassServer
from server.host.processes.start_pacing import SKIPPED_MOST, MachineStartPacer
from server.host.settings import ClassroomSettings, LabSettings, Listening, Settings, WorldLimits

CODE = "TEST42"
TARGET = {"x": 5.0, "y": 5.0, "z": 10.0}
VECTOR3 = "geometry_msgs/msg/Vector3"
BURST = 5
HOVER_S = 6.0  # a world's drone climbs to its 3 m hover in about 5 s


def class_settings(
    *,
    max_worlds: int = 3,
    classroom: bool = True,
    world: dict[str, Any] | None = None,
    workspaces_dir: Path = Path("workspaces"),
    **lab: Any,
) -> Settings:
    """A class of ``max_worlds`` worlds; ``lab`` overrides its worlds' LabSettings, ``world`` their
    WorldLimits, ``workspaces_dir`` the folder of their workspaces; ``classroom=False``: the same
    lab alone."""
    lab_settings = LabSettings(
        **{"launch": "all", "launch_args": {"start_delay": "3600"}, "viewer": False, **lab}
    )
    limits = WorldLimits(**{"writes_hz": 1.0, "writes_burst": BURST, **(world or {})})
    return Settings(
        listen=Listening(allowed_hosts=("testserver",)),
        lab=lab_settings,
        classroom=ClassroomSettings(
            code=CODE, max_worlds=max_worlds, world=limits, workspaces_dir=workspaces_dir
        )
        if classroom
        else None,
    )


@pytest.fixture
def clock() -> ManualClock:
    return ManualClock(1_000.0)


@pytest.fixture
def client(clock: ManualClock) -> Iterator[TestClient]:
    with TestClient(create_app(class_settings(), clock)) as test_client:
        yield test_client


def classroom(client: TestClient) -> ClassServer:
    return client.app.state.classroom  # type: ignore[attr-defined,no-any-return]


def join(client: TestClient, name: str, code: str = CODE) -> str:
    reply = client.post("/api/classroom/join", json={"name": name, "code": code})
    assert reply.status_code == 201, reply.text
    client.cookies.clear()  # each call below says whose token it carries
    return str(reply.json()["token"])


def auth(token: str, world: str | None = None) -> dict[str, str]:
    headers = {"Authorization": f"Bearer {token}"}
    if world is not None:
        headers["X-Lab-World"] = world
    return headers


def advance(client: TestClient, clock: ManualClock, seconds: float) -> None:
    """Move every world's time on together: at each deadline of any world's timers, every world
    runs what is due (as Executor.spin_until does for one), so no world's timers run late."""
    labs = [w.lab for w in classroom(client).worlds.values()]
    end = clock.now() + seconds

    def run() -> None:
        for lab in labs:
            lab.executor.spin_some()
        while (deadline := min(lab.executor.next_deadline_s() for lab in labs)) <= end:
            clock.set(max(deadline, clock.now()))
            for lab in labs:
                lab.executor.spin_some()
        clock.set(max(end, clock.now()))
        for lab in labs:
            lab.executor.spin_some()

    assert client.portal is not None
    client.portal.call(run)


def drone(client: TestClient, token: str) -> tuple[float, float, float]:
    latest = client.get("/api/topics/uav/sensors/gps", headers=auth(token)).json()["latest"]
    p = latest["pose"]["position"]
    return p["x"], p["y"], p["z"]


# -- joining -------------------------------------------------------------------------------------
def test_join_gives_a_world_and_an_http_only_same_site_cookie(client: TestClient) -> None:
    reply = client.post("/api/classroom/join", json={"name": "Ada Lovelace", "code": CODE.lower()})
    assert reply.status_code == 201, reply.text
    assert reply.json()["world"] == "ada_lovelace"
    cookie = reply.headers["set-cookie"].lower()
    assert "lab_token=" in cookie and "httponly" in cookie and "samesite=strict" in cookie
    me = client.get("/api/classroom/me")  # the cookie alone identifies the page
    assert me.json() == {
        "role": "student",
        "world": "ada_lovelace",
        "name": "Ada Lovelace",
        "class_code": None,
    }


@pytest.mark.parametrize(
    ("body", "status", "says"),
    [
        ({"name": "Eve", "code": "WRONG1"}, 403, "wrong class code"),
        ({"name": "---", "code": CODE}, 422, "at least one letter"),
        ({"name": "Eve", "code": 42}, 422, "code"),
        ({"name": "Eve", "code": CODE, "world": "ada"}, 422, "world"),
    ],
)
def test_a_bad_join_is_refused_by_name_and_starts_no_world(
    client: TestClient, body: dict[str, Any], status: int, says: str
) -> None:
    reply = client.post("/api/classroom/join", json=body)
    assert reply.status_code == status and says in reply.text
    assert classroom(client).worlds == {}


def test_a_taken_name_is_409_and_a_full_class_429(client: TestClient) -> None:
    join(client, "Ada")
    taken = client.post("/api/classroom/join", json={"name": "ADA", "code": CODE})
    assert taken.status_code == 409 and "taken" in taken.text
    join(client, "Bob")
    join(client, "Cy")
    full = client.post("/api/classroom/join", json={"name": "Dee", "code": CODE})
    assert full.status_code == 429 and "full" in full.text
    assert set(classroom(client).worlds) == {"ada", "bob", "cy"}


# -- isolation -----------------------------------------------------------------------------------
@pytest.mark.parametrize("token", [None, "junk", "e30.e30"])
def test_without_a_valid_token_the_worlds_are_closed(client: TestClient, token: str | None) -> None:
    join(client, "Ada")
    headers = {} if token is None else auth(token)
    assert client.get("/api/topics", headers=headers).status_code == 401
    assert (
        client.post(
            "/api/publish", headers=headers, json={"topic": "/abort_takeoff", "msg": {"data": True}}
        ).status_code
        == 401
    )
    assert refusal(client, "/ws/keys", headers=headers).code == CloseCode.UNAUTHORIZED


def test_one_students_token_on_another_students_world_is_403(client: TestClient) -> None:
    ada, bob = join(client, "Ada"), join(client, "Bob")
    for headers in (auth(ada, "bob"), {**auth(ada), "X-Lab-World": "bob"}):
        assert client.get("/api/topics", headers=headers).status_code == 403
        publish = client.post(
            "/api/publish", headers=headers, json={"topic": "/abort_takeoff", "msg": {"data": True}}
        )
        assert publish.status_code == 403 and "'ada'" in publish.text
    assert client.get("/api/topics?world=bob", headers=auth(ada)).status_code == 403
    assert client.post("/api/classroom/worlds/bob/reset", headers=auth(ada)).status_code == 403
    for path in ("/ws/keys", "/ws/topics/keydown"):
        assert refusal(client, path, headers=auth(ada, "bob")).code == CloseCode.FORBIDDEN
    # Nothing reached Bob's world.
    assert client.get("/api/topics/abort_takeoff", headers=auth(bob)).json()["publish_count"] == 0


def test_a_setpoint_flies_only_its_own_worlds_drone(client: TestClient, clock: ManualClock) -> None:
    ada, bob = join(client, "Ada"), join(client, "Bob")
    advance(client, clock, HOVER_S)  # both drones take off and hover at their home
    home = drone(client, bob)
    reply = client.post(
        "/api/publish",
        headers=auth(ada),
        json={"topic": "/uav/input/position", "msg": TARGET, "type": VECTOR3},
    )
    assert reply.status_code == 200, reply.text
    advance(client, clock, 4.0)
    x, y, z = drone(client, ada)
    assert x > 1.0 and y > 1.0 and z > home[2] + 1.0  # on its way to (5, 5, 10)
    bx, by, bz = drone(client, bob)
    assert abs(bx - home[0]) < 0.05 and abs(by - home[1]) < 0.05 and abs(bz - home[2]) < 0.05


def test_a_flooding_student_is_limited_in_their_own_world_only(client: TestClient) -> None:
    ada, bob = join(client, "Ada"), join(client, "Bob")
    body = {"topic": "/abort_takeoff", "msg": {"data": False}}
    codes = [client.post("/api/publish", headers=auth(ada), json=body).status_code for _ in range(BURST + 3)]
    assert codes == [200] * BURST + [429] * 3  # the clock is still: no write comes back
    assert client.post("/api/publish", headers=auth(bob), json=body).status_code == 200
    assert client.get("/api/topics", headers=auth(ada)).status_code == 200  # reading is not limited


# -- the instructor ------------------------------------------------------------------------------
def test_the_instructor_sees_every_world_and_must_name_one_to_act_in_it(client: TestClient) -> None:
    ada = join(client, "Ada")
    join(client, "Bob")
    teacher = classroom(client).instructor_token
    listed = client.get("/api/classroom/worlds", headers=auth(teacher)).json()
    assert listed["class_code"] == CODE and [w["world"] for w in listed["worlds"]] == ["ada", "bob"]
    assert all(w["crashed_nodes"] == [] and w["keys_held"] == [] for w in listed["worlds"])
    assert client.get("/api/classroom/worlds", headers=auth(ada)).status_code == 403
    assert client.get("/api/topics", headers=auth(teacher)).status_code == 400
    assert client.get("/api/topics", headers=auth(teacher, "bob")).status_code == 200
    assert client.get("/api/topics", headers=auth(teacher, "nobody")).status_code == 404


def test_resetting_one_world_leaves_the_other_as_it_was(client: TestClient, clock: ManualClock) -> None:
    ada, bob = join(client, "Ada"), join(client, "Bob")
    teacher = classroom(client).instructor_token
    for token in (ada, bob):
        started = client.post(
            "/api/publishers",
            headers=auth(token),
            json={"topic": "/uav/input/position", "msg": TARGET, "type": VECTOR3, "rate_hz": 1.0},
        )
        assert started.status_code == 201, started.text
    advance(client, clock, 3.0)
    ada_before, bob_before = drone(client, ada), drone(client, bob)
    assert bob_before[0] > 0.5  # both on their way
    reply = client.post("/api/classroom/worlds/bob/reset", headers=auth(teacher))
    assert reply.status_code == 200 and reply.json()["resets"] == 1
    # Bob's world starts over (no publisher, the drone back home); Ada's keeps its publisher and flight.
    assert client.get("/api/publishers", headers=auth(bob)).json() == []
    assert len(client.get("/api/publishers", headers=auth(ada)).json()) == 1
    assert drone(client, ada) == ada_before
    advance(client, clock, 1.0)
    assert drone(client, ada)[0] > ada_before[0]
    assert abs(drone(client, bob)[0]) < 0.05


def test_a_removed_students_token_stops_working(client: TestClient) -> None:
    ada, bob = join(client, "Ada"), join(client, "Bob")
    teacher = classroom(client).instructor_token
    assert client.delete("/api/classroom/worlds/bob", headers=auth(teacher)).status_code == 200
    assert client.get("/api/topics", headers=auth(bob)).status_code == 401
    assert client.get("/api/topics", headers=auth(ada)).status_code == 200
    assert client.delete("/api/classroom/worlds/bob", headers=auth(teacher)).status_code == 404
    assert client.delete("/api/classroom/worlds/ada", headers=auth(ada)).status_code == 403


def test_a_broadcast_reaches_every_world(client: TestClient) -> None:
    ada, bob = join(client, "Ada"), join(client, "Bob")
    teacher = classroom(client).instructor_token
    reply = client.post(
        "/api/classroom/broadcast",
        headers=auth(teacher),
        json={"topic": "/uav/input/position", "msg": TARGET, "type": VECTOR3},
    )
    assert reply.json() == {"reached": ["ada", "bob"], "refused": {}}
    for token in (ada, bob):
        assert client.get("/api/topics/uav/input/position", headers=auth(token)).json()["publish_count"] == 1
    wrong = client.post(
        "/api/classroom/broadcast",
        headers=auth(teacher),
        json={"topic": "/uav/input/position", "msg": {"data": 1}, "type": "std_msgs/msg/Int64"},
    )
    assert wrong.status_code == 422 and "no world took" in wrong.text


# -- the pages -----------------------------------------------------------------------------------
def test_the_page_is_the_join_form_until_the_browser_has_a_world(client: TestClient) -> None:
    assert 'id="join"' in client.get("/").text
    join(client, "Ada")
    reply = client.post("/api/classroom/join", json={"name": "Bea", "code": CODE})
    assert reply.status_code == 201
    page = client.get("/")  # the cookie the join set
    assert 'id="join"' not in page.text and "/static/build/lab.js" in page.text


def test_the_instructors_link_sets_the_cookie_and_leaves_the_address_bar(client: TestClient) -> None:
    teacher = classroom(client).instructor_token
    assert client.get("/instructor").status_code == 401
    assert client.get("/instructor", params={"token": "junk"}).status_code == 403
    reply = client.get("/instructor", params={"token": teacher}, follow_redirects=False)
    assert reply.status_code == 303 and reply.headers["location"] == "/instructor"
    assert "httponly" in reply.headers["set-cookie"].lower()
    page = client.get("/instructor")
    assert page.status_code == 200 and "/static/build/instructor.js" in page.text


def test_a_single_lab_app_has_no_classroom() -> None:
    settings = Settings(
        listen=Listening(allowed_hosts=("testserver",)), lab=LabSettings(launch="rocket", viewer=False)
    )
    with TestClient(create_app(settings)) as single:
        assert single.post("/api/classroom/join", json={"name": "Ada", "code": CODE}).status_code == 404
        assert single.get("/instructor").status_code == 404
        assert single.get("/api/topics").status_code == 200  # no token needed on one's own machine
        document = single.get("/openapi.json").json()
        assert not [path for path in document["paths"] if path.startswith("/api/classroom/")]
        assert "security" not in document and "securitySchemes" not in document["components"]


CLASS_ROUTES = {
    "/api/classroom/join": {"post"},
    "/api/classroom/leave": {"post"},
    "/api/classroom/me": {"get"},
    "/api/classroom/worlds": {"get"},
    "/api/classroom/workers": {"get"},
    "/api/classroom/host": {"post"},
    "/api/classroom/worlds/{name}/reset": {"post"},
    "/api/classroom/reset": {"post"},
    "/api/classroom/worlds/{name}": {"delete"},
    "/api/classroom/broadcast": {"post"},
    "/api/classroom/worlds/{name}/workspace/files": {"get"},
    "/api/classroom/worlds/{name}/workspace/files/{path}": {"get"},
    "/api/classroom/workspaces/archive": {"get"},
}


def test_the_class_servers_openapi_documents_its_routes_and_the_token(client: TestClient) -> None:
    document = client.get("/openapi.json").json()
    paths = document["paths"]
    assert {path: set(paths[path]) for path in CLASS_ROUTES if path in paths} == CLASS_ROUTES
    assert set(document["components"]["securitySchemes"]) == {"bearer", "cookie"}
    assert document["components"]["securitySchemes"]["cookie"]["name"] == "lab_token"
    assert document["security"] == [{"bearer": []}, {"cookie": []}]

    join_op = paths["/api/classroom/join"]["post"]
    assert join_op["security"] == []  # joining needs the class code, not a token
    assert join_op["requestBody"]["content"]["application/json"]["schema"]["$ref"].endswith("/JoinRequest")
    assert join_op["responses"]["201"]["content"]["application/json"]["schema"]["$ref"].endswith("/Joined")
    assert {"403", "409", "429"} <= set(join_op["responses"]) and "401" not in join_op["responses"]
    assert paths["/api/health"]["get"]["security"] == []
    for path, methods in CLASS_ROUTES.items():
        for method in methods:
            operation = paths[path][method]
            if operation.get("security") != []:
                assert "401" in operation["responses"], (path, method)

    # A world's operation: the instructor names the world in a header; a student may be refused it.
    publish = paths["/api/publish"]["post"]
    assert "X-Lab-World" in [p["name"] for p in publish["parameters"] if p["in"] == "header"]
    assert {"401", "403", "404", "429"} <= set(publish["responses"])
    assert "429" not in paths["/api/topics"]["get"]["responses"]  # reads are not rate-limited

    # What the document says of /me is what the route answers, for a student and the instructor.
    me_schema = document["components"]["schemas"]["Me"]
    assert set(me_schema["required"]) == {"role", "world", "name"}
    ada = client.get("/api/classroom/me", headers=auth(join(client, "Ada"))).json()
    assert ada == {"role": "student", "world": "ada", "name": "Ada", "class_code": None}
    teacher = client.get("/api/classroom/me", headers=auth(classroom(client).instructor_token)).json()
    assert teacher["role"] == "instructor" and teacher["class_code"] == CODE and teacher["world"] is None


# -- physics that scales -------------------------------------------------------------------------
def fly(others: list[str], simple: bool = False) -> list[tuple[float, float, float]]:
    """Ada's drone flying on a fresh class server, among up to 3 ``others`` flying elsewhere; her
    positions at every 0.25 s. Rotor physics: she flies to TARGET. ``simple``: every world flies
    the lab's kinematic simple_sim, whose controller waits 5 s; until then each drone takes a new
    velocity from REST every second, at a time between two of the batch's ticks."""
    clock = ManualClock(1_000.0)
    args = {"start_delay": "3600", "simple": "true" if simple else "false"}
    with TestClient(create_app(class_settings(max_worlds=8, launch_args=args), clock)) as client:
        clock.set(clock.now() + 0.031)  # her timers keep a phase of their own, not the batch's
        tokens = {"Ada": join(client, "Ada")}
        for i in range(3):  # the others' timers keep phases of their own, 13 ms apart
            advance(client, clock, 0.013)
            if i < len(others):
                tokens[others[i]] = join(client, others[i])
        shared = classroom(client).labs.simple_physics if simple else classroom(client).labs.physics
        assert len(shared) == len(tokens)  # every drone in the one batch
        track = []
        for step in range(16):
            if step == 0 or (simple and step % 4 == 0):
                for i, (name, token) in enumerate(tokens.items()):
                    topic, msg = (
                        ("/uav/input/velocity", {"x": 1.0 + step / 4, "y": 0.5 * i, "z": 1.0})
                        if simple
                        else (
                            "/uav/input/position",
                            TARGET if name == "Ada" else {"x": -i, "y": 2 * i, "z": 1 + i},
                        )
                    )
                    reply = client.post(
                        "/api/publish",
                        headers=auth(token),
                        json={"topic": topic, "msg": msg, "type": VECTOR3},
                    )
                    assert reply.status_code == 200, reply.text
            advance(client, clock, 0.25)
            track.append(drone(client, tokens["Ada"]))
        return track


@pytest.mark.parametrize("simple", [False, True], ids=["rotor_physics", "simple_sim"])
def test_a_world_flies_the_same_alone_or_among_others(simple: bool) -> None:
    alone = fly([], simple)
    among = fly(["Bob", "Cy", "Dee"], simple)
    assert alone[-1][0] > 1.0  # she is flying, not sitting on the pad
    assert among == alone  # float for float: the others' drones share her batch, not her flight


def test_a_reset_world_leaves_the_simple_batch_and_comes_back_at_the_origin(clock: ManualClock) -> None:
    args = {"start_delay": "3600", "simple": "true"}
    with TestClient(create_app(class_settings(launch_args=args), clock)) as client:
        ada, bob = join(client, "Ada"), join(client, "Bob")
        for token in (ada, bob):
            reply = client.post(
                "/api/publish",
                headers=auth(token),
                json={"topic": "/uav/input/position", "msg": TARGET, "type": VECTOR3},
            )
            assert reply.status_code == 200, reply.text
        advance(client, clock, 7.0)  # the simple mode's controller waits 5 s, then flies
        assert drone(client, ada)[2] > 1.0 and drone(client, bob)[2] > 1.0
        teacher = classroom(client).instructor_token
        assert client.post("/api/classroom/worlds/bob/reset", headers=auth(teacher)).status_code == 200
        assert len(classroom(client).labs.simple_physics) == 2  # Bob's old drone left, his new one joined
        advance(client, clock, 0.2)
        assert abs(drone(client, bob)[2]) < 0.1  # Bob starts over at the origin (GPS noise is 0.01 m)
        assert drone(client, ada)[2] > 1.0  # Ada keeps her flight


def test_a_reset_closes_the_worlds_sockets_so_the_page_reconnects_to_the_new_world(
    client: TestClient,
) -> None:
    bob = join(client, "Bob")
    teacher = classroom(client).instructor_token
    with (
        client.websocket_connect("/ws/keys", headers=auth(bob)) as keys,
        client.websocket_connect("/ws/topics/countdown", headers=auth(bob)) as echo,
    ):
        assert client.post("/api/classroom/worlds/bob/reset", headers=auth(teacher)).status_code == 200
        for ws in (keys, echo):
            closed = receive_within(ws)
            assert closed["type"] == "websocket.close" and closed["code"] == CloseCode.SERVICE_RESTART
    with client.websocket_connect("/ws/keys", headers=auth(bob)) as keys:  # as keys.js reconnects
        keys.send_json({"type": "keydown", "key": "b"})
        lab = classroom(client).get("bob").lab

        def held() -> set[int]:
            assert client.portal is not None
            return client.portal.call(lab.keyboard.held)

        deadline = 50
        while not held() and deadline:
            deadline -= 1
            keys.send_json({"type": "heartbeat"})
        assert held() == {ord("b")}  # the new world's keyboard has the key


def test_leaving_forgets_the_browsers_cookie_and_the_world_stays(client: TestClient) -> None:
    reply = client.post("/api/classroom/join", json={"name": "Ada", "code": CODE})
    assert reply.status_code == 201
    assert client.get("/api/classroom/me").status_code == 200  # the join's cookie
    left = client.post("/api/classroom/leave")
    assert left.status_code == 200 and "lab_token=" in left.headers["set-cookie"]
    assert client.get("/api/classroom/me").status_code == 401
    assert "ada" in classroom(client).worlds


def test_the_class_starts_yield_to_its_worlds_skipped_ticks(client: TestClient, clock: ManualClock) -> None:
    """The class's start pacer reads what its worlds' timers skipped (server/classroom/lateness.py,
    server/host/processes/start_pacing.py): while every world keeps its ticks a start leaves the
    turns after it where they were; once one world's loop gave it no turn for half a second, the
    next start moves them back, and the machine's slots file says how much was skipped."""
    join(client, "Ada"), join(client, "Bob")
    labs = classroom(client).labs
    labs.skipped.window_s = 0.0  # a reading on every ask: the test's clock is the manual one
    advance(client, clock, 1.0)
    assert labs.skipped.read() == 0.0  # the worlds counted from here on
    advance(client, clock, 1.0)
    pacer = labs.start_pacer
    pacer.hold_s = 1e-6  # a slot freed again by the next ask: each start here goes at once
    assert labs.skipped.read() == 0.0 and pacer.admit() is None and pacer.stretched == 0
    clock.advance(0.5)  # Ada's world gets a turn, Bob's none, after half a second
    ada = classroom(client).worlds["ada"].lab
    assert ada is not None and client.portal is not None
    client.portal.call(ada.executor.spin_some)
    assert pacer.admit() is None and pacer.stretched == 1
    assert isinstance(pacer, MachineStartPacer)
    said = json.loads(pacer.path.read_text())["skipped"]
    assert max(share for _at, share in said.values()) >= SKIPPED_MOST
