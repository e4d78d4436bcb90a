"""``--workers``: world workers a class server starts on its own machine, N at its start or (auto,
the default) one per spare core as the class grows.

The class server runs as a process of its own on loopback and starts its workers itself; the
tests find them by the ids the server reports (``started_here``), check them in /proc, and end
every process they saw by its id, whatever happens.
"""

from __future__ import annotations

import os
import signal
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import httpx
import pytest
from support.app import READY_S, App, instructor_token, wait_for_workers
from support.http import HTTP
from support.wait import wait_until

from server.__main__ import main as server_main
from server.base.cores import usable_cores

CODE = "LOC042"
GONE_WAIT_S = 30.0  # a worker polls for its parent twice a second; its worlds then end


@dataclass
class Class:
    app: App
    instructor: str
    seen_pids: set[int] = field(default_factory=set)

    def get(self, path: str, token: str | None = None) -> httpx.Response:
        headers = {"Authorization": f"Bearer {token or self.instructor}"}
        return HTTP.get(self.app.url + path, headers=headers, timeout=10)

    def started_here(self) -> list[dict[str, Any]]:
        reply = self.get("/api/classroom/workers")
        assert reply.status_code == 200, reply.text
        found: list[dict[str, Any]] = reply.json()["started_here"]
        self.seen_pids |= {w["pid"] for w in found if w["pid"] is not None}
        return found

    def worlds(self) -> dict[str, dict[str, Any]]:
        return {w["world"]: w for w in self.get("/api/classroom/worlds").json()["worlds"]}


def alive(pid: int) -> bool:
    """A process that exists and is not a zombie waiting for its (new) parent to reap it."""
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except (FileNotFoundError, ProcessLookupError):
        return False
    return state != "Z"


def parent_of(pid: int) -> int:
    return int(Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[1])


def end_pids(pids: set[int]) -> None:
    for pid in pids:
        if alive(pid):
            os.kill(pid, signal.SIGKILL)


def join(klass: Class, name: str) -> str:
    reply = HTTP.post(f"{klass.app.url}/api/classroom/join", json={"name": name, "code": CODE}, timeout=60)
    assert reply.status_code == 201, reply.text
    world: str = reply.json()["world"]
    return world


def start_class(root: Path, *extra: str) -> Class:
    app = App(root, "--classroom", "--class-code", CODE, "--launch", "rocket", "--no-foxglove", *extra)
    return Class(app, instructor_token(app.log_tail(10**6)))


@pytest.fixture
def klass(tmp_path: Path) -> Iterator[Class]:
    # The class server keeps one world itself; its one worker takes the rest.
    started = start_class(tmp_path, "--local-worlds", "1", "--workers", "1")
    try:
        wait_for_workers(started.app.url, started.instructor, {"local-1"})
        yield started
    finally:
        started.app.stop()
        end_pids(started.seen_pids)


def test_a_class_server_starts_its_workers_places_worlds_on_them_and_ends_them_with_it(klass: Class) -> None:
    (worker,) = klass.started_here()
    assert worker["id"] == "local-1" and worker["restarts"] == 0
    pid = worker["pid"]
    assert parent_of(pid) == klass.app.proc.pid  # a child of the class server, not a stray process
    command_line = Path(f"/proc/{pid}/cmdline").read_bytes().decode()
    assert "world-worker" in command_line
    assert klass.instructor not in command_line  # the token goes in its environment only
    assert "World workers on this machine: 1" in klass.app.log_tail(10**6)
    cores = usable_cores()  # this machine's, as the class server reads them (the default budget, 15 a core)
    assert f"This machine takes {15 * cores} worlds (15 a core, {cores} cores" in klass.app.log_tail(10**6)

    tokens = {}
    for name in ("Ada", "Bob"):  # one at a time: each placement sees the one before
        reply = HTTP.post(
            f"{klass.app.url}/api/classroom/join", json={"name": name, "code": CODE}, timeout=60
        )
        assert reply.status_code == 201, reply.text
        tokens[reply.json()["world"]] = reply.json()["token"]
    placed = {world: row["worker"] for world, row in klass.worlds().items()}
    assert sorted(placed.values(), key=str) == [None, "local-1"]  # one on the worker, one at home
    remote = next(world for world, where in placed.items() if where == "local-1")
    nodes = klass.get("/api/nodes", tokens[remote])  # through the class server, as a local world
    assert nodes.status_code == 200, nodes.text
    assert "/CountDownNode" in {n["name"] for n in nodes.json()}

    klass.app.stop()  # Ctrl-C: the class server ends its worker by its id
    wait_until(lambda: not alive(pid), f"worker {pid} ends with its class server", GONE_WAIT_S, poll_s=0.2)


def test_the_console_shows_the_class_not_every_worlds_node_lines_which_stay_on_their_rosout(
    klass: Class,
) -> None:
    tokens = {}
    for name in ("Ada", "Bob"):
        reply = HTTP.post(
            f"{klass.app.url}/api/classroom/join", json={"name": name, "code": CODE}, timeout=60
        )
        assert reply.status_code == 201, reply.text
        tokens[reply.json()["world"]] = reply.json()["token"]
    assert sorted((row["worker"] for row in klass.worlds().values()), key=str) == [None, "local-1"]

    def counting(world: str) -> bool:
        # The rocket's main controller logs each second of the countdown (the handout's output).
        reply = klass.get("/api/topics/rosout", tokens[world])
        latest = reply.json().get("latest") if reply.status_code == 200 else None
        return latest is not None and str(latest["msg"]).startswith("Countdown:")

    for world in tokens:  # one world here, one on the worker: both proxied or served by the server
        wait_until(
            lambda world=world: counting(world), f"{world}'s countdown on its /rosout", READY_S, poll_s=0.2
        )
    console = klass.app.log_tail(10**6)
    assert "Ada joined: world ada" in console and "Bob joined: world bob" in console  # the class's own events
    assert "at warning and above, each under its world's name" in console  # the banner says where the rest is
    # Neither world's info lines, nor a line per request (the polls above), nor the proxy's own calls.
    assert "Countdown:" not in console and "Rocket Ready for Countdown" not in console, console[-3000:]
    assert "/api/topics/rosout" not in console and "httpx" not in console, console[-3000:]


def test_a_worker_that_dies_is_started_again_and_its_world_comes_back(klass: Class) -> None:
    reply = HTTP.post(f"{klass.app.url}/api/classroom/join", json={"name": "Ada", "code": CODE}, timeout=60)
    assert reply.status_code == 201, reply.text
    world, token = reply.json()["world"], reply.json()["token"]
    assert klass.worlds()[world]["worker"] == "local-1"
    (first,) = klass.started_here()
    os.kill(first["pid"], signal.SIGKILL)

    def restarted() -> bool:
        (now,) = klass.started_here()
        return now["pid"] not in (None, first["pid"]) and now["restarts"] == 1

    wait_until(restarted, "the class server starts its worker again", READY_S, poll_s=0.2)
    wait_for_workers(klass.app.url, klass.instructor, {"local-1"})

    def back() -> bool:
        row = klass.worlds()[world]
        return (
            row["moves"] == 1
            and row["worker"] is not None
            and klass.get("/api/nodes", token).status_code == 200
        )

    wait_until(back, f"world {world} hosted again", READY_S + GONE_WAIT_S, poll_s=0.2)


def test_a_killed_class_server_leaves_no_worker_behind(tmp_path: Path) -> None:
    started = start_class(tmp_path, "--workers", "1")
    try:
        wait_for_workers(started.app.url, started.instructor, {"local-1"})
        (worker,) = started.started_here()
        started.app.proc.kill()  # no chance to end anything itself
        started.app.proc.wait(timeout=10)
        wait_until(
            lambda: not alive(worker["pid"]), "an orphaned worker ends by itself", GONE_WAIT_S, poll_s=0.2
        )
    finally:
        started.app.stop()
        end_pids(started.seen_pids)


def test_by_default_a_worker_starts_as_the_class_grows_and_takes_the_next_worlds(tmp_path: Path) -> None:
    spare = len(os.sched_getaffinity(0)) - 1  # the class server runs on the cores this test may use
    klass = start_class(tmp_path, "--spread-at", "2")  # --workers auto, the default
    try:
        assert klass.get("/api/classroom/workers").json()["spread"] == {"at_worlds": 2, "up_to": spare}
        if spare:
            assert f"one each 2 worlds, at most {spare} (its spare cores)" in klass.app.log_tail(10**6)
        join(klass, "Ada")
        assert klass.started_here() == []  # a class of one: no other process
        join(klass, "Bob")  # two worlds: a worker for the joins after them
        assert [w["id"] for w in klass.started_here()] == ["local-1"][:spare]
        if spare:
            (worker,) = klass.started_here()
            assert parent_of(worker["pid"]) == klass.app.proc.pid
            # It takes turns at the machine's node-start slots with the class server: their file.
            argv = Path(f"/proc/{worker['pid']}/cmdline").read_bytes().decode().split("\0")
            assert argv[argv.index("--start-slots") + 1] == str(
                (tmp_path / "state" / "start-slots").resolve()
            )
            wait_for_workers(klass.app.url, klass.instructor, {"local-1"})
        cy = join(klass, "Cy")
        assert klass.worlds()[cy]["worker"] == ("local-1" if spare else None)
        join(klass, "Dee")  # four worlds call for two workers: at most one per spare core
        assert len(klass.started_here()) == min(spare, 2)
        placed = sorted((row["worker"] for row in klass.worlds().values()), key=str)
        assert placed == ([None, None, "local-1", "local-1"] if spare else [None] * 4)  # even
    finally:
        klass.app.stop()
        end_pids(klass.seen_pids)
    for pid in klass.seen_pids:  # stopped with the class server, by their ids
        wait_until(lambda pid=pid: not alive(pid), f"worker {pid} ends with its class server", GONE_WAIT_S)


def test_workers_0_starts_none_however_large_the_class(tmp_path: Path) -> None:
    klass = start_class(tmp_path, "--workers", "0", "--spread-at", "1")
    try:
        assert klass.get("/api/classroom/workers").json()["spread"] is None
        join(klass, "Ada")
        join(klass, "Bob")
        assert klass.started_here() == []
        assert "World workers on this machine" not in klass.app.log_tail(10**6)
    finally:
        klass.app.stop()
        end_pids(klass.seen_pids)


@pytest.mark.parametrize(
    ("argv", "said"),
    [
        (["--workers", "1"], "--workers needs --classroom"),  # no --classroom
        (["--classroom", "--workers", "1", "--no-zenoh"], "--workers needs --classroom"),
        # not its own router
        (
            ["--classroom", "--workers", "1", "--zenoh-connect", "tcp/127.0.0.1:7447"],
            "--workers needs --classroom",
        ),
        (["--classroom", "--workers", "33"], "--workers needs --classroom"),
        (["--classroom", "--workers", "-1"], "--workers needs --classroom"),
        (["--classroom", "--workers", "some"], "N or auto, not 'some'"),
        (["--classroom", "--spread-at", "0"], "spread_at"),
    ],
)
def test_workers_flag_refused_where_it_cannot_work(
    argv: list[str], said: str, capsys: pytest.CaptureFixture[str]
) -> None:
    with pytest.raises(SystemExit) as exited:
        server_main(argv)
    assert exited.value.code == 2
    assert said in capsys.readouterr().err
