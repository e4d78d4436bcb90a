"""compose.class.yml's class, run as processes: the class server and two world workers started
with the commands and settings the file gives its services (read from the file, so this follows
it), with loopback addresses, free ports and a folder of their own each in place of a container's;
the workers deriving the instructor's token from the class secret file the class server reads too.
A student joins, their world is placed on a worker, and the drone flies to a setpoint published
with their token. Both read the class secret from a file (the file's secret, mounted as a file in
each container: a test's file here), and a worker given another secret is refused by the router.
Every Zenoh session on loopback, with multicast scouting off (the app's own
sessions never scout); every process ended by its own id.
"""

from __future__ import annotations

import math
import os
import re
import secrets
import socket
import subprocess
import sys
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest
from support.app import READY_S, LoggedProcess, free_ports, instructor_token, wait_for_workers, wait_healthy
from support.deployment import class_compose, option, server_args, swapped, worker_argv
from support.forked_server import start_server
from support.http import HTTP
from support.wait import wait_until

from server.base.loop_priority import scheduling_of
from server.classroom.tokens import instructor_token as derived_instructor_token
from server.classroom.tokens import read_class_secret
from server.classroom.worker_control import TOKEN_ENV
from server.world_worker import _router_refuses

TARGET = (5.0, 5.0, 10.0)
FLIGHT_S = 90.0  # a loaded 2-core machine; the flight itself takes about 15 s


class Process(LoggedProcess):
    """``python -m server ARGS`` in ``cwd`` (its state, workspaces and bags there, as in /app)."""

    def __init__(self, args: list[str], cwd: Path, env: dict[str, str] | None = None) -> None:
        cwd.mkdir()
        self.log_path = cwd / "out.log"
        self._log = self.log_path.open("w")
        self.proc = start_server(args, cwd=cwd, log=self.log_path, env=env)


def worker_id(pid: int) -> str:
    """A worker's id when its command names none: HOSTNAME-PID (server/world_worker.py)."""
    return re.sub(r"[^A-Za-z0-9_-]", "_", f"{socket.gethostname()}-{pid}")[:64]


def healthcheck(service: dict[str, Any], port: int) -> subprocess.CompletedProcess[str]:
    """The service's own health check, run here against ``port`` instead of the container's."""
    test = service["healthcheck"]["test"]
    assert test[:2] == ["CMD", "python"], test
    script = test[3]
    url = re.search(r"http://127\.0\.0\.1:(\d+)/api/health", script)
    assert url is not None, script
    return subprocess.run(
        [sys.executable, *test[2:3], script.replace(url.group(0), f"http://127.0.0.1:{port}/api/health")],
        capture_output=True, text=True, timeout=30, check=False,
    )  # fmt: skip


@dataclass
class Class:
    server: Process
    url: str
    workers: list[Process]
    worker_ports: list[int]

    def logs(self) -> str:
        return "\n".join(p.log_tail(2000) for p in (self.server, *self.workers))


def class_secret(path: Path, secret: str | None = None) -> Path:
    """A class secret file, as the operator makes one (``openssl rand -hex 32``)."""
    path.write_text((secret or secrets.token_hex(32)) + "\n")
    return path


def without_token() -> dict[str, str]:
    """This environment without ROS2LAB_TOKEN: a worker given the class secret file takes no other."""
    return {k: v for k, v in os.environ.items() if k != TOKEN_ENV}


def start_class_server(tmp_path: Path, secret_file: Path) -> tuple[Process, str, int, str, str]:
    """compose.class.yml's class server, on loopback and free ports, reading ``secret_file`` where
    its container reads the mounted secret: the process, its URL, its router's port, the
    instructor's token its banner shows and the class code."""
    classroom = class_compose()["classroom"]
    port, router, foxglove = free_ports(3)
    args = swapped(server_args(classroom["command"]), {
        "--host": "127.0.0.1", "--port": str(port), "--zenoh-listen": f"tcp/127.0.0.1:{router}",
        "--class-secret-file": str(secret_file),
    })  # fmt: skip
    # The file leaves the instructor's Foxglove port at its default (8765): a free one here.
    server = Process([*args, "--foxglove-port", str(foxglove)], tmp_path / "classroom", without_token())
    url = f"http://127.0.0.1:{port}"
    try:
        wait_healthy(url, server.proc, READY_S, server.log_tail)
    except BaseException:
        server.stop()
        raise
    banner = server.log_tail(10**6)
    code = re.search(r"join with class code (\S+)", banner)
    assert code is not None, banner
    return server, url, router, instructor_token(banner), code.group(1)


def worker_args(router: int, port: int, secret_file: Path) -> list[str]:
    """compose.class.yml's worker command, on loopback, reading ``secret_file``."""
    worker = class_compose()["worker"]
    # Nothing from the class server's log: the secret file is all a worker is given.
    assert "environment" not in worker, worker.get("environment")
    argv = worker_argv(worker["command"])
    # ... and they join the router the class server opens, by the service's name.
    router_port = option(server_args(class_compose()["classroom"]["command"]), "--zenoh-listen").rsplit(
        ":", 1
    )[1]
    assert option(argv, "--connect") == f"tcp/classroom:{router_port}", argv
    # Both services read the same file (the one secret compose mounts in each).
    assert option(argv, "--class-secret-file") == option(
        class_compose()["classroom"]["command"], "--class-secret-file"
    )
    return swapped(server_args(argv), {
        "--connect": f"tcp/127.0.0.1:{router}", "--host": "127.0.0.1", "--port": str(port),
        "--advertise": "127.0.0.1", "--class-secret-file": str(secret_file),
    })  # fmt: skip


@pytest.fixture
def compose_class(tmp_path: Path) -> Iterator[tuple[Class, dict[str, Any], str, str]]:
    services = class_compose()
    secret_file = class_secret(tmp_path / "class-secret")
    worker_ports = free_ports(2)
    server, url, router, token, code = start_class_server(tmp_path, secret_file)
    started = Class(server, url, [], worker_ports)
    try:
        # The instructor's token a worker derives from the file is the one the class server issued.
        assert token == derived_instructor_token(read_class_secret(secret_file))
        for n, wport in enumerate(worker_ports, start=1):
            args = worker_args(router, wport, secret_file)
            started.workers.append(Process(args, tmp_path / f"worker-{n}", without_token()))
        ids = {worker_id(w.proc.pid) for w in started.workers}
        wait_for_workers(url, token, ids)
        yield started, services, token, code
    finally:
        server.stop()  # first: a class server that stops frees its workers' worlds
        for process in started.workers:
            process.stop()


def test_the_compose_class_runs_as_processes_and_a_students_drone_flies_on_a_worker(
    compose_class: tuple[Class, dict[str, Any], str, str],
) -> None:
    klass, services, instructor, code = compose_class
    instructor_auth = {"Authorization": f"Bearer {instructor}"}
    # Each service's health check answers against its process.
    server_port = int(klass.url.rsplit(":", 1)[1])
    checks = [(services["classroom"], server_port)] + [(services["worker"], p) for p in klass.worker_ports]
    for service, port in checks:
        done = healthcheck(service, port)
        assert done.returncode == 0, done.stderr

    joined = HTTP.post(f"{klass.url}/api/classroom/join", json={"name": "Ada", "code": code}, timeout=60)
    assert joined.status_code == 201, joined.text
    auth = {"Authorization": f"Bearer {joined.json()['token']}"}
    worlds = HTTP.get(f"{klass.url}/api/classroom/worlds", headers=instructor_auth, timeout=10).json()[
        "worlds"
    ]
    (ada,) = worlds
    workers = {w.proc.pid: w for w in klass.workers}
    assert ada["worker"] in {worker_id(pid) for pid in workers}, ada  # never the class server itself

    def gps() -> dict[str, Any] | None:
        reply = HTTP.get(f"{klass.url}/api/topics/uav/sensors/gps", headers=auth, timeout=10)
        return reply.json()["latest"] if reply.status_code == 200 else None

    wait_until(gps, "a GPS fix from Ada's world on its worker", FLIGHT_S, poll_s=0.25, detail=klass.logs)
    reply = HTTP.post(
        f"{klass.url}/api/publish", headers=auth, timeout=30,
        json={"topic": "/uav/input/position", "msg": dict(zip("xyz", TARGET, strict=True))},
    )  # fmt: skip
    assert reply.status_code == 200, reply.text

    def near_target() -> bool:
        latest = gps()
        if latest is None:
            return False
        p = latest["pose"]["position"]
        return math.dist((p["x"], p["y"], p["z"]), TARGET) < 1.0

    wait_until(near_target, "Ada's drone at (5, 5, 10)", FLIGHT_S, poll_s=0.25, detail=klass.logs)
    for process in (klass.server, *klass.workers):
        assert process.proc.poll() is None, process.log_tail()
    # Each process's worlds' loop (its first thread) runs in the real-time class, as root may, and
    # the instructor's load says so for each place as the kernel does.
    loops = {"server": klass.server.proc.pid} | {worker_id(pid): pid for pid in workers}
    assert {place: scheduling_of(pid) for place, pid in loops.items()} == dict.fromkeys(loops, "realtime")
    load = HTTP.get(f"{klass.url}/api/classroom/load", headers=instructor_auth, timeout=10).json()
    said = {p["place"]: p["cpu"]["loop"] for p in load["places"] if p["cpu"] is not None}
    assert said == dict.fromkeys(loops, "realtime"), load["places"]


def test_a_worker_given_another_class_secret_is_refused_by_the_router_naming_its_file(tmp_path: Path) -> None:
    own = class_secret(tmp_path / "class-secret")
    server, _url, router, _token, _code = start_class_server(tmp_path, own)
    try:
        other = class_secret(tmp_path / "another-secret")
        (wport,) = free_ports(1)
        worker = Process(worker_args(router, wport, other), tmp_path / "worker", without_token())
        try:
            worker.proc.wait(timeout=READY_S)
        finally:
            worker.stop()
        out = worker.log_path.read_text()
        assert worker.proc.returncode == 2, out
        assert (
            f"the class secret file {other}" in out and "router lets in only the class's own workers" in out
        ), out
        assert server.proc.poll() is None, server.log_tail()
        # The control: the same check lets in a login derived from the class server's own file.
        endpoint = f"tcp/127.0.0.1:{router}"
        assert _router_refuses(endpoint, derived_instructor_token(read_class_secret(own)), "own") is None
        assert _router_refuses(endpoint, derived_instructor_token(read_class_secret(other)), "other")
    finally:
        server.stop()
