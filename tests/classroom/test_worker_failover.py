"""When a world worker or the class server goes away: a class server starts a gone
worker's worlds again elsewhere, under the same names and tokens and with their progress (the
class server's copy, handed to a worker whose own folder never held it); a worker frees its worlds when
the class server has said no hello for its orphan timeout; hellos not sealed with the class's
token get no answer.

The first tests step a manual clock; the last run a class server and two workers as processes of
their own on loopback, end one of each by its id, and watch the rest carry on.
"""

from __future__ import annotations

import json
import math
import os
import signal
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import httpx
import pytest
from fastapi.testclient import TestClient
from support.app import App, WorldWorker, instructor_token, wait_for_workers
from support.http import HTTP
from support.wait import wait_until as support_wait_until

from node_runtime.bus import ManualClock
from server.app import create_app
from server.classroom import WorldWorker as WorkerWorlds
from server.classroom.workers import (
    MAX_REPLY_BYTES,
    Silence,
    genuine_hello,
    hello_request,
    seal,
    worker_api_token,
)
from server.host.settings import ClassroomSettings, LabSettings, Listening, Settings, WorkerSettings

CLASS_TOKEN = "the-instructors-token"
ORPHAN_S = 5.0
CODE = "FAIL42"
# The processes' timeouts: a few hello periods, so a loaded machine never takes a live peer for a
# gone one. The class server's is also longer than a world worker's restart takes (a new process
# importing the lab and opening its session: over 8 s once in a whole-suite run on three xdist
# workers), since the test restarts one within it.
WORKER_TIMEOUT_S = 15.0
ORPHAN_TIMEOUT_S = 6.0
GONE_WAIT_S = 90.0
TARGET = (5.0, 5.0, 10.0)


# -- silence, on a manual clock ------------------------------------------------------------------
def test_a_peer_is_silent_only_after_the_whole_timeout_since_it_was_last_heard() -> None:
    silence = Silence(10.0)
    assert silence.silent({"wa"}, 100.0) == set()  # first asked: it gets the whole timeout
    silence.heard("wa", 105.0)
    assert silence.silent({"wa"}, 114.9) == set()
    assert silence.silent({"wa"}, 115.0) == {"wa"}
    assert silence.silent({"wa", "wb"}, 115.0) == {"wa"}  # wb is new: not silent yet
    assert silence.silent({"wb"}, 120.0) == set()  # wa is no longer asked about: forgotten
    assert silence.silent({"wa", "wb"}, 125.0) == {"wb"}  # wa asked again: a new timeout from now


# -- hellos --------------------------------------------------------------------------------------
def test_only_a_hello_sealed_with_the_class_token_is_genuine() -> None:
    assert genuine_hello(CLASS_TOKEN, hello_request(CLASS_TOKEN, "n0nce")) == "n0nce"
    assert genuine_hello(CLASS_TOKEN, hello_request("another-class", "n0nce")) is None
    plain = json.dumps({"op": "hello", "nonce": "n0nce"}).encode()  # what a stranger could send
    assert genuine_hello(CLASS_TOKEN, plain) is None
    assert genuine_hello(CLASS_TOKEN, seal(CLASS_TOKEN, {"op": "host", "nonce": "n0nce"})) is None
    assert genuine_hello(CLASS_TOKEN, seal(CLASS_TOKEN, {"op": "hello", "nonce": "x" * 65})) is None
    assert genuine_hello(CLASS_TOKEN, b"\xff garbage") is None
    assert genuine_hello(CLASS_TOKEN, b" " * (MAX_REPLY_BYTES + 1)) is None


# -- a worker whose class server is gone, on a manual clock -----------------------------------------
@pytest.fixture
def clock() -> ManualClock:
    return ManualClock(1_000.0)


@pytest.fixture
def worker_client(clock: ManualClock) -> Iterator[TestClient]:
    settings = Settings(
        listen=Listening(allowed_hosts=("testserver",)),
        lab=LabSettings(launch="rocket", launch_args={"start_delay": "3600"}, viewer=False),
        classroom=ClassroomSettings(max_worlds=3),
        worker=WorkerSettings(
            id="wm", url="http://127.0.0.1:1", class_token=CLASS_TOKEN, orphan_timeout_s=ORPHAN_S
        ),
    )
    with TestClient(create_app(settings, clock)) as test_client:
        yield test_client


def host(client: TestClient, world: str, domain_id: int) -> None:
    body = {
        "world": world,
        "student": world.title(),
        "domain_id": domain_id,
        "launch": "rocket",
        "launch_args": {"start_delay": "3600"},
    }
    reply = client.post("/api/classroom/host", json=body, headers=worker_auth("wm"))
    assert reply.status_code == 201, reply.text


def worker_auth(worker_id: str, class_token: str = CLASS_TOKEN) -> dict[str, str]:
    return {"Authorization": f"Bearer {worker_api_token(class_token, worker_id)}"}


def test_a_worker_frees_its_worlds_once_the_class_server_is_silent_for_its_orphan_timeout(
    worker_client: TestClient, clock: ManualClock
) -> None:
    classroom: WorkerWorlds = worker_client.app.state.classroom  # type: ignore[attr-defined]
    portal = worker_client.portal
    assert portal is not None
    host(worker_client, "ada", 3)
    host(worker_client, "bob", 4)
    labs = [w.lab for w in classroom.worlds.values()]
    clock.advance(ORPHAN_S - 1.0)
    assert portal.call(classroom.free_if_orphaned, ORPHAN_S) == []
    # The class server's calls (and its hellos, in Zenoh's thread) count as hearing from it.
    reply = worker_client.get("/api/classroom/worlds", headers=worker_auth("wm"))
    assert sorted(w["world"] for w in reply.json()["worlds"]) == ["ada", "bob"]
    clock.advance(ORPHAN_S - 1.0)
    assert portal.call(classroom.free_if_orphaned, ORPHAN_S) == []
    # A caller without the class's token is not the class server: it keeps no world alive.
    assert worker_client.get("/api/classroom/worlds", headers=worker_auth("wm", "not-it")).status_code == 401
    clock.advance(1.0)
    assert sorted(portal.call(classroom.free_if_orphaned, ORPHAN_S)) == ["ada", "bob"]
    assert classroom.worlds == {}
    assert all(lab is not None and lab.bus.nodes == [] for lab in labs)  # every node ended
    reply = worker_client.get("/api/classroom/worlds", headers=worker_auth("wm"))
    assert reply.status_code == 200 and reply.json()["worlds"] == []
    host(worker_client, "ada", 3)  # a new class server may place worlds here again
    assert list(classroom.worlds) == ["ada"]


# -- processes: a worker dies, then the class server -----------------------------------------------
def api(url: str, path: str, token: str, **headers: str) -> httpx.Response:
    return HTTP.get(url + path, headers={"Authorization": f"Bearer {token}", **headers}, timeout=10)


def wait_until(check: Any, what: str, logs: Any, timeout_s: float = GONE_WAIT_S) -> Any:
    """support.wait's wait, with a failover's long default and the class server's log on failure."""
    return support_wait_until(check, what, timeout_s, poll_s=0.25, detail=logs)


def worker(tmp_path: Path, app: App, instructor: str, wid: str) -> WorldWorker:
    """World worker ``wid`` with a state folder of its own (as on another machine): a world's
    progress on it is its own, and the class server keeps a copy (progress_copies.py)."""
    return WorldWorker(
        tmp_path,
        app.router,
        instructor,
        wid,
        "--max-worlds",
        "1",
        "--orphan-timeout",
        str(ORPHAN_TIMEOUT_S),
        "--state-dir",
        str(tmp_path / f"state-{wid}"),
    )


def answer_of(app: App, token: str) -> str | None:
    """Ada's answer to q1, as her world (wherever it runs) gives it."""
    reply = api(app.url, "/api/checkpoints", token)
    if reply.status_code != 200:
        return None
    return next(q["answer"] for q in reply.json()["questions"] if q["id"] == "q1")


@pytest.fixture
def failover_class(tmp_path: Path) -> Iterator[tuple[App, dict[str, WorldWorker], str]]:
    # Every world on a worker (--local-worlds 0), each worker for one world: a gone worker's world
    # can only go to the other.
    app = App(
        tmp_path,
        "--classroom",
        "--class-code",
        CODE,
        "--launch",
        "fly",
        "--local-worlds",
        "0",
        "--no-foxglove",
        "--worker-timeout",
        str(WORKER_TIMEOUT_S),
    )
    workers: dict[str, WorldWorker] = {}
    try:
        instructor = instructor_token(app.log_tail(10**6))
        for wid in ("wa", "wb"):
            workers[wid] = worker(tmp_path, app, instructor, wid)
        wait_for_workers(app.url, instructor, {"wa", "wb"})
        yield app, workers, instructor
    finally:
        for started in workers.values():
            started.stop()
        app.stop()


def test_a_gone_workers_world_starts_again_on_another_and_a_gone_class_server_frees_it(
    failover_class: tuple[App, dict[str, WorldWorker], str], tmp_path: Path
) -> None:
    app, workers, instructor = failover_class
    joined = HTTP.post(f"{app.url}/api/classroom/join", json={"name": "Ada", "code": CODE}, timeout=60)
    assert joined.status_code == 201, joined.text
    token = joined.json()["token"]

    def ada() -> dict[str, Any]:
        worlds = api(app.url, "/api/classroom/worlds", instructor).json()["worlds"]
        return next(w for w in worlds if w["world"] == "ada")

    first = ada()["worker"]
    assert first in workers and ada()["moves"] == 0
    other = next(w for w in workers if w != first)
    other_url = next(
        w["url"]
        for w in api(app.url, "/api/classroom/workers", instructor).json()["workers"]
        if w["id"] == other
    )
    domain = ada()["domain_id"]
    # Ada answers a question in her world on the first worker, which keeps it in its own folder;
    # the class server copies it at its next round of hellos.
    answered = HTTP.put(
        f"{app.url}/api/checkpoints/answers/q1",
        headers={"Authorization": f"Bearer {token}"},
        json={"text": "four nodes"},
        timeout=30,
    )
    assert answered.status_code == 200, answered.text
    copy = tmp_path / "state" / "progress" / "ada" / "progress.json"
    wait_until(
        lambda: copy.is_file() and "four nodes" in copy.read_text(), "the class server's copy", app.log_tail
    )
    assert not (tmp_path / f"state-{other}" / "progress" / "ada").exists()

    os.kill(workers[first].proc.pid, signal.SIGKILL)  # no goodbye: the worker is just gone
    workers[first].proc.wait(timeout=10)
    moved = wait_until(
        lambda: (w := ada())["moves"] == 1 and w["lost"] is None and w, "ada's world to move", app.log_tail
    )
    assert moved["worker"] == other and moved["domain_id"] == domain
    assert f"world worker {first} lost world ada (no hello for" in app.log_tail(10**6)
    # Her answer went with the world to a worker whose folder never held it.
    assert answer_of(app, token) == "four nodes"

    # The student's token opens the new world, which flies.
    def gps() -> dict[str, Any] | None:
        reply = api(app.url, "/api/topics/uav/sensors/gps", token)
        return reply.json()["latest"] if reply.status_code == 200 else None

    wait_until(gps, "a GPS fix from ada's new world", app.log_tail)
    reply = HTTP.post(
        f"{app.url}/api/publish",
        headers={"Authorization": f"Bearer {token}"},
        timeout=30,
        json={"topic": "/uav/input/position", "msg": dict(zip("xyz", TARGET, strict=True))},
    )
    assert reply.status_code == 200, reply.text

    def near_target() -> bool:
        latest = gps()
        if latest is None:
            return False
        p = latest["pose"]["position"]
        return math.dist((p["x"], p["y"], p["z"]), TARGET) < 1.0

    wait_until(near_target, "ada's drone at (5, 5, 10) in its new world", app.log_tail)

    # The worker that hosts it now restarts under the same id, faster than --worker-timeout: it
    # answers hellos again, but without ada's world, which then starts again (here, or there).
    os.kill(workers[other].proc.pid, signal.SIGKILL)
    workers[other].proc.wait(timeout=10)
    workers[other].stop()
    workers[other] = restarted = worker(tmp_path, app, instructor, other)
    again = wait_until(
        lambda: (w := ada())["moves"] == 2 and w["lost"] is None and w,
        "ada's world to start again",
        app.log_tail,
    )
    assert again["worker"] == other  # the only worker with room: the restarted one
    assert f"world worker {other} lost world ada (it answers but no longer hosts" in app.log_tail(10**6)
    wait_until(gps, "a GPS fix from ada's world on the restarted worker", app.log_tail)
    assert answer_of(app, token) == "four nodes"
    other_url = next(
        w["url"]
        for w in api(app.url, "/api/classroom/workers", instructor).json()["workers"]
        if w["id"] == other
    )
    assert restarted.proc.poll() is None

    # The class server goes without a goodbye: the worker frees the world nobody can reach.
    os.kill(app.proc.pid, signal.SIGKILL)
    app.proc.wait(timeout=10)

    # (Watched in its log: a call with the class's token would count as the class server's.)
    wait_until(
        lambda: "no hello from the class server" in workers[other].log_tail(10**6),
        f"worker {other} to free ada's world",
        workers[other].log_tail,
    )
    reply = api(other_url, "/api/classroom/worlds", worker_api_token(instructor, other))
    assert reply.status_code == 200 and reply.json()["worlds"] == []
    assert workers[other].proc.poll() is None  # the worker stays, for the next class server
