"""Students' code in worlds on world workers: a worker that shares the class's workspaces folder
serves a student's workspace and runs their node, as a world on the class server does; one that
keeps a folder of its own serves it from there, and the class server keeps its own copy in step
(server/classroom/workspace_copies.py); a world moved by failover keeps its files, to a worker that
shares the folder or to one that does not.

A class server that hosts no world itself and world workers, each a process of its own on
loopback, ended by their ids: ``wa`` and later ``wb`` on the class's folder, ``wc`` and later
``wd`` on folders of their own. Each worker hosts one world, so where each world goes is known.
"""

from __future__ import annotations

import os
import signal
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import httpx
import pytest
from support.app import App, WorldWorker, instructor_token, wait_for_workers
from support.http import HTTP
from support.wait import wait_until

from server.host.processes.sandbox import probe

CODE = "WSW042"
WORKER_TIMEOUT_S = 8.0  # a few hello periods, so a loaded machine never takes a live worker for gone
ORPHAN_TIMEOUT_S = 6.0
MOVE_WAIT_S = 90.0
NODE_PATH = "src/hello_pkg/hello_pkg/hello.py"
NODE = """import rclpy
from rclpy.node import Node


def main():
    rclpy.init()
    node = Node('hello')
    print(f'hello from {node.get_name()}', flush=True)
    node.destroy_node()
    rclpy.try_shutdown()
"""


@dataclass
class Class:
    app: App
    workdir: Path
    shared: Path  # the class's workspaces folder
    apart: Path  # wc's own
    apart_too: Path  # wd's own
    instructor: str
    tokens: dict[str, str]  # world → its student's token
    workers: dict[str, WorldWorker]

    def call(self, method: str, path: str, token: str, body: Any = None, **headers: str) -> httpx.Response:
        return HTTP.request(
            method,
            self.app.url + path,
            json=body,
            timeout=30,
            headers={"Authorization": f"Bearer {token}", **headers},
        )

    def worlds(self) -> dict[str, dict[str, Any]]:
        reply = self.call("GET", "/api/classroom/worlds", self.instructor)
        assert reply.status_code == 200, reply.text
        return {w["world"]: w for w in reply.json()["worlds"]}

    def on(self, worker: str) -> str:
        """The world that worker ``worker`` hosts."""
        return next(name for name, w in self.worlds().items() if w["worker"] == worker)

    def add_workers(self, folders: dict[str, Path]) -> None:
        """Start a worker (one world at most) on each folder, and wait until the class finds them."""
        for worker_id, workspaces in folders.items():
            self.workers[worker_id] = WorldWorker(
                self.workdir,
                self.app.router,
                self.instructor,
                worker_id,
                "--max-worlds",
                "1",
                "--orphan-timeout",
                str(ORPHAN_TIMEOUT_S),
                "--workspaces-dir",
                str(workspaces),
                cwd=self.workdir,
            )
        alive = {worker_id for worker_id, worker in self.workers.items() if worker.proc.poll() is None}
        wait_for_workers(self.app.url, self.instructor, alive)


@pytest.fixture(scope="module")
def klass(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Class]:
    workdir = tmp_path_factory.mktemp("class")
    shared, apart, apart_too = workdir / "workspaces", workdir / "apart", workdir / "apart_too"
    app = App(
        workdir,
        "--classroom",
        "--class-code",
        CODE,
        "--launch",
        "rocket",
        "--local-worlds",
        "0",
        "--no-foxglove",
        "--worker-timeout",
        str(WORKER_TIMEOUT_S),
        "--workspaces-dir",
        str(shared),
        cwd=workdir,
    )
    klass = Class(app, workdir, shared, apart, apart_too, instructor_token(app.log_tail(10**6)), {}, {})
    try:
        klass.add_workers({"wa": shared, "wc": apart})
        for student in ("Ada", "Bob"):
            joined = HTTP.post(
                f"{app.url}/api/classroom/join", json={"name": student, "code": CODE}, timeout=60
            )
            assert joined.status_code == 201, joined.text
            klass.tokens[joined.json()["world"]] = joined.json()["token"]
        yield klass
    finally:
        for worker in klass.workers.values():
            worker.stop()
        app.stop()


def output_of(klass: Class, token: str, group: str) -> list[str]:
    reply = klass.call("GET", f"/api/launches/{group}/output", token)
    assert reply.status_code == 200, reply.text
    return [line for p in reply.json()["processes"] for line in p["lines"]]


def instructor_reads(klass: Class, world: str, path: str) -> str | None:
    """The file as the instructor's page reads it: from the class server's own folder."""
    read = klass.call("GET", f"/api/classroom/worlds/{world}/workspace/files/{path}", klass.instructor)
    return str(read.json()["text"]) if read.status_code == 200 else None


def test_a_worker_world_serves_and_runs_its_code_on_the_classs_folder_or_its_own(klass: Class) -> None:
    shared_world, apart_world = klass.on("wa"), klass.on("wc")
    token, apart_token = klass.tokens[shared_world], klass.tokens[apart_world]

    # On wc, which keeps another folder: saved there, and copied to the class's folder within a round.
    saved = klass.call("PUT", f"/api/workspace/files/{NODE_PATH}", apart_token, {"text": NODE})
    assert saved.status_code == 201, saved.text
    assert (klass.apart / apart_world / NODE_PATH).read_text() == NODE
    tree = klass.call("GET", "/api/workspace/files", apart_token).json()
    assert NODE_PATH in [e["path"] for e in tree["entries"]]
    wait_until(lambda: instructor_reads(klass, apart_world, NODE_PATH) == NODE, "the class's copy", 30.0)
    assert (klass.shared / apart_world / NODE_PATH).read_text() == NODE
    # A removal there goes to the copy too.
    extra = "src/hello_pkg/notes.txt"
    assert klass.call("PUT", f"/api/workspace/files/{extra}", apart_token, {"text": "x\n"}).status_code == 201
    wait_until(lambda: instructor_reads(klass, apart_world, extra) == "x\n", "the new file's copy", 30.0)
    assert klass.call("DELETE", f"/api/workspace/files/{extra}", apart_token).status_code in (200, 204)
    wait_until(lambda: not (klass.shared / apart_world / extra).exists(), "the removal copied", 30.0)

    # On wa, on the class's folder: a new package, a node saved in it, and Run.
    made = klass.call(
        "POST",
        "/api/workspace/packages",
        token,
        {"name": "hello_pkg", "build_type": "ament_python", "node_name": "hello"},
    )
    assert made.status_code == 201, made.text
    saved = klass.call("PUT", f"/api/workspace/files/{NODE_PATH}", token, {"text": NODE})
    assert saved.status_code == 200, saved.text
    assert (klass.shared / shared_world / NODE_PATH).read_text() == NODE
    tree = klass.call("GET", "/api/workspace/files", token).json()
    assert NODE_PATH in [e["path"] for e in tree["entries"]]
    read = klass.call(
        "GET", f"/api/classroom/worlds/{shared_world}/workspace/files/{NODE_PATH}", klass.instructor
    )
    assert read.status_code == 200 and read.json()["text"] == NODE

    why = probe()
    if why is not None and os.environ.get("CI") != "true":
        pytest.skip(f"no sandbox on this machine to run a student's node in: {why}")
    run = klass.call("POST", "/api/run", token, {"package": "hello_pkg", "executable": "hello"})
    assert run.status_code == 201, run.text + klass.workers["wa"].log_tail()
    group = run.json()["id"]
    wait_until(
        lambda: "hello from hello" in output_of(klass, token, group),
        "the student's node's line",
        60.0,
        poll_s=0.25,
        detail=lambda: f"{output_of(klass, token, group)}\n{klass.workers['wa'].log_tail()}",
    )


def saved_world(klass: Class, worker: str) -> tuple[str, str, str]:
    """The world on ``worker``, its student's token and its node file's route, the file saved."""
    world = klass.on(worker)
    token = klass.tokens[world]
    path = f"/api/workspace/files/{NODE_PATH}"
    if klass.call("GET", path, token).status_code == 404:  # this test alone: save it here
        assert klass.call("PUT", path, token, {"text": NODE}).status_code == 201
    return world, token, path


def fail_over(klass: Class, world: str, gone: str, to: str, folder: Path) -> None:
    """Start worker ``to`` on ``folder`` (the one place with room once ``gone`` is), kill ``gone``
    with no goodbye, and wait for ``world`` to start again on ``to``."""
    klass.add_workers({to: folder})
    os.kill(klass.workers[gone].proc.pid, signal.SIGKILL)
    klass.workers[gone].proc.wait(timeout=10)
    moved = wait_until(
        lambda: (w := klass.worlds()[world])["moves"] == 1 and w["lost"] is None and w,
        f"{world}'s world to move",
        MOVE_WAIT_S,
        poll_s=0.25,
        detail=klass.app.log_tail,
    )
    assert moved["worker"] == to


def test_a_world_moved_by_failover_keeps_its_files(klass: Class) -> None:
    world, token, path = saved_world(klass, "wa")
    before = klass.call("GET", path, token)
    assert before.status_code == 200, before.text
    fail_over(klass, world, "wa", "wb", klass.shared)

    # The same file, by its version: what wb serves is what wa saved.
    after = klass.call("GET", path, token)
    assert after.status_code == 200, after.text
    assert after.json() == before.json()
    # And it saves over that version there, into the class's folder.
    etag = after.json()["etag"]
    saved = klass.call("PUT", path, token, {"text": NODE + "# moved\n"}, **{"If-Match": f'"{etag}"'})
    assert saved.status_code == 200, saved.text
    assert (klass.shared / world / NODE_PATH).read_text().endswith("# moved\n")
    stale = klass.call("PUT", path, token, {"text": "stale\n"}, **{"If-Match": f'"{etag}"'})
    assert stale.status_code == 412


def test_a_world_on_a_folder_of_its_own_moved_by_failover_keeps_its_files(klass: Class) -> None:
    world, token, path = saved_world(klass, "wc")
    wait_until(lambda: instructor_reads(klass, world, NODE_PATH) == NODE, "the class's copy", 30.0)
    fail_over(klass, world, "wc", "wd", klass.apart_too)
    # wd's own folder never held it: the class's copy was handed over with the world.
    after = klass.call("GET", path, token)
    assert after.status_code == 200, after.text
    assert after.json()["text"] == NODE
    assert (klass.apart_too / world / NODE_PATH).read_text() == NODE
