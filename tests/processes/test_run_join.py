"""``ros2lab run`` joins only the graph its lab names, and says so when it cannot: against a
lab that accepts and never replies, or where nothing listens, one line and a non-zero exit within
``--join-timeout`` (and no node starts); against one that answers late, the node joins the router
and domain the answer names. A node process whose router is not there says so within seconds.

The labs here are stand-ins written for the test (a silent socket, a tiny HTTP server) and the
router a Zenoh router this test opens, all on 127.0.0.1 without scouting."""

from __future__ import annotations

import json
import os
import select
import signal
import socket
import subprocess
import sys
import threading
import time
from collections.abc import Iterator
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from typing import Any

import pytest
import zenoh
from support.app import end, free_port
from support.wait import wait_until

from server.cli.environment import TOKEN_ENV
from server.cli.priority import START_NICE

from .conftest import make_workspace

NODE = """
import rclpy
from rclpy.node import Node


class LateJoiner(Node):
    def __init__(self):
        super().__init__('late_joiner')


if __name__ == '__main__':
    rclpy.init()
    try:
        rclpy.spin(LateJoiner())
    except KeyboardInterrupt:
        pass
    finally:
        rclpy.try_shutdown()
"""
JOIN_TIMEOUT_S = 3.0
ROS2LAB = "import sys; from server.cli import main; sys.exit(main())"  # what the ros2lab command runs
DOMAIN = 7


@pytest.fixture(scope="module")
def workspace(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return make_workspace(tmp_path_factory.mktemp("run_join"), {"src/demo/late_joiner.py": NODE})


def ros2lab_run(
    url: str,
    workspace: Path,
    *extra: str,
    token: str | None = None,
    python: tuple[str, ...] = (),
    executable: str = "late_joiner.py",
) -> subprocess.Popen[str]:
    """``ros2lab run`` of the late joiner against ``url``, as the ``ros2lab`` command runs it;
    ``python``: options for the interpreter."""
    env = {k: v for k, v in os.environ.items() if k not in ("ROS_DOMAIN_ID", "ROS2LAB_WORKSPACE", TOKEN_ENV)}
    if token is not None:
        env[TOKEN_ENV] = token
    return subprocess.Popen(
        [
            sys.executable,
            *python,
            "-c",
            ROS2LAB,
            "--url",
            url,
            "run",
            "--workspace",
            str(workspace),
            "--join-timeout",
            str(JOIN_TIMEOUT_S),
            *extra,
            "demo",
            executable,
        ],
        env=env,
        text=True,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )


def refused_within_bound(proc: subprocess.Popen[str]) -> tuple[int, str, float]:
    started = time.monotonic()
    try:
        _out, err = proc.communicate(timeout=JOIN_TIMEOUT_S + 30)
    except subprocess.TimeoutExpired:
        end(proc)
        proc.communicate()
        pytest.fail("ros2lab run kept waiting past its bound")
    return proc.returncode, err, time.monotonic() - started


def test_run_against_a_lab_that_never_replies_is_one_line_and_a_non_zero_exit(workspace: Path) -> None:
    with socket.socket() as silent:
        silent.bind(("127.0.0.1", 0))
        silent.listen(16)  # the kernel accepts; nothing ever reads or replies
        url = f"http://127.0.0.1:{silent.getsockname()[1]}"
        code, err, took = refused_within_bound(ros2lab_run(url, workspace))
    lines = err.strip().splitlines()
    assert code != 0 and len(lines) == 1, err
    assert "did not tell how to join its graph within 3 s" in lines[0] and "not started" in lines[0]
    assert took < JOIN_TIMEOUT_S + 20  # the bound, plus the interpreter's start on a loaded machine


@pytest.mark.parametrize("token", [None, "a-students-token"], ids=["no token", "a token"])
def test_run_with_a_token_is_below_the_worlds_before_it_asks_the_lab(
    workspace: Path, token: str | None
) -> None:
    """A lab behind a token serves others, whose students' nodes run below its worlds: the command
    takes that priority before its imports, so twenty started at once on the lab's machine do not
    import at the worlds' priority (server/cli/priority.py). Read while it asks a socket that
    never answers; without a token it runs as it was started."""
    with socket.socket() as silent:
        silent.bind(("127.0.0.1", 0))
        silent.listen(16)
        silent.settimeout(60)
        proc = ros2lab_run(f"http://127.0.0.1:{silent.getsockname()[1]}", workspace, token=token)
        try:
            conn, _ = silent.accept()
            with conn:
                conn.settimeout(60)
                assert conn.recv(4096).startswith(b"GET /api/zenoh/join")  # it is asking now
                nice = os.getpriority(os.PRIO_PROCESS, proc.pid)
        finally:
            end(proc)
            proc.communicate()
    own = os.getpriority(os.PRIO_PROCESS, 0)
    assert nice == (min(19, own + START_NICE) if token else own)


def test_run_asks_the_lab_having_imported_little_more_than_the_interpreter(workspace: Path) -> None:
    """Sixty students' ``ros2lab run`` at once share the class's machine (or their own small
    ones), and none has asked for its turn until all have nearly done what they do first: the
    command asks the lab over a plain socket (server/cli/plain_get.py) with neither httpx nor the
    standard library's HTTP client and its email package imported, finds its file (the package
    index) while it waits for its turn, and imports neither the message types (the node's own
    process loads them), a WebSocket client (only the echo verbs open one) nor what the node's
    command needs (its login, the runner's command line, subprocess). Read from ``python -X
    importtime`` while it asks a socket that never answers."""
    with socket.socket() as silent:
        silent.bind(("127.0.0.1", 0))
        silent.listen(16)
        silent.settimeout(60)
        url = f"http://127.0.0.1:{silent.getsockname()[1]}"
        proc = ros2lab_run(url, workspace, python=("-X", "importtime"))
        try:
            conn, _ = silent.accept()
            with conn:
                conn.settimeout(60)
                assert conn.recv(4096).startswith(b"GET /api/zenoh/join")  # it is asking now
        finally:
            end(proc)
            _out, err = proc.communicate()
    imported = {
        line.rsplit("|", 1)[1].strip() for line in err.splitlines() if line.startswith("import time:")
    }
    assert {"server.cli.plain_get", "socket"} <= imported, err[-2000:]  # what it does need
    later = (
        "node_runtime.msgs",
        "node_runtime.ament",
        "websockets",
        "zenoh",
        "httpx",
        "http.client",
        "email",
        "ssl",
        "dataclasses",
        "subprocess",
        "node_runtime.transport.acl",
    )
    heavy = sorted(m for m in imported if m.startswith(later) or m == "server.host.processes.command")
    assert heavy == [], heavy


def test_run_where_nothing_listens_is_one_line_and_a_non_zero_exit(workspace: Path) -> None:
    url = f"http://127.0.0.1:{free_port()}"
    code, err, _took = refused_within_bound(ros2lab_run(url, workspace))
    assert code != 0 and err.strip().splitlines() == [
        f"error: the lab at {url} did not tell how to join its graph within 3 s (connection refused); "
        "the node was not started"
    ]


class LateLab:
    """A stand-in lab on ``port``: it answers the join with ``join`` (and ``status``, ``headers``)."""

    def __init__(
        self, port: int, join: dict[str, Any], status: int = 200, headers: dict[str, str] | None = None
    ) -> None:
        body = json.dumps(join).encode()
        self.asked: list[str] = []
        asked = self.asked

        class Handler(BaseHTTPRequestHandler):
            def do_GET(self) -> None:
                asked.append(self.path)
                ok = self.path.startswith("/api/zenoh/join")
                self.send_response(status if ok else 404)
                for name, value in (headers or {}).items() if ok else ():
                    self.send_header(name, value)
                self.send_header("Content-Type", "application/json")
                payload = body if ok else b'{"detail": "Not Found"}'
                self.send_header("Content-Length", str(len(payload)))
                self.end_headers()
                self.wfile.write(payload)

            def log_message(self, *args: object) -> None:
                pass

        self.server = ThreadingHTTPServer(("127.0.0.1", port), Handler)
        self.thread = threading.Thread(target=self.server.serve_forever, daemon=True)
        self.thread.start()

    def close(self) -> None:
        self.server.shutdown()
        self.server.server_close()


def test_run_finds_its_file_while_it_waits_for_its_turn_and_a_missing_one_ends_it_at_once(
    workspace: Path,
) -> None:
    """A lab pacing a class's starts gives this one its turn a minute away: the command looks for
    its file meanwhile, and one that is not there is ros2 run's one line and exit 1 at once, not a
    minute later (nor is the lab asked again)."""
    port = free_port()
    wait = {"Retry-After": "60", "Retry-After-Ms": "60000", "Start-Turn": "kept-for-this-start"}
    lab = LateLab(port, {"detail": "the lab is starting other nodes first"}, status=429, headers=wait)
    try:
        code, err, _took = refused_within_bound(
            ros2lab_run(f"http://127.0.0.1:{port}", workspace, executable="no_such_node.py")
        )
    finally:
        lab.close()
    assert code == 1 and err.strip().splitlines() == [
        "No executable found: package 'demo' has no executable 'no_such_node.py' "
        "(it has: late_joiner, late_joiner.py)"
    ], err
    assert lab.asked == ["/api/zenoh/join?start=true&turn=new"]


@pytest.fixture
def router() -> Iterator[tuple[zenoh.Session, str]]:
    endpoint = f"tcp/127.0.0.1:{free_port()}"
    config = zenoh.Config()
    config.insert_json5("mode", '"router"')
    config.insert_json5("scouting/multicast/enabled", "false")
    config.insert_json5("listen/endpoints", json.dumps([endpoint]))
    session = zenoh.open(config)
    try:
        yield session, endpoint
    finally:
        session.close()


def node_tokens(session: zenoh.Session, name: str) -> list[str]:
    """The liveliness keys of nodes named ``name`` on the router's graph (rmw_zenoh's ``@ros2_lv``)."""
    keys = [
        str(reply.ok.key_expr) for reply in session.liveliness().get("@ros2_lv/**", timeout=2.0) if reply.ok
    ]
    return [k for k in keys if k.endswith("/" + name) and "/NN/" in k]


def test_run_against_a_lab_that_answers_late_joins_the_graph_it_names(
    workspace: Path, router: tuple[zenoh.Session, str]
) -> None:
    session, endpoint = router
    port = free_port()
    join = {"router": endpoint, "domain_id": DOMAIN, "user": None, "password": None, "env": {}}
    run = ros2lab_run(f"http://127.0.0.1:{port}", workspace, "--join-timeout", "60")
    lab: LateLab | None = None
    try:
        time.sleep(1.5)  # the lab is not up yet: its port refuses the first asks
        assert run.poll() is None
        lab = LateLab(port, join)
        wait_until(
            lambda: node_tokens(session, "late_joiner"), "the node on the named router", 60, poll_s=0.2
        )
        (token,) = node_tokens(session, "late_joiner")
        assert token.startswith(f"@ros2_lv/{DOMAIN}/"), token
        assert lab.asked == ["/api/zenoh/join?start=true&turn=new"]
        run.send_signal(signal.SIGINT)
        _out, err = run.communicate(timeout=30)
        assert run.returncode == 0, err
    finally:
        end(run)
        run.communicate()  # and its pipes closed
        if lab is not None:
            lab.close()


def test_a_node_process_without_its_router_says_so_within_seconds(workspace: Path) -> None:
    env = {
        **os.environ,
        "PYTHONUNBUFFERED": "1",
        "ZENOH_CONFIG_OVERRIDE": f'connect/endpoints=["tcp/127.0.0.1:{free_port()}"]',
    }
    node = subprocess.Popen(
        [sys.executable, "-m", "node_runtime.process.runner", str(workspace / "src/demo/late_joiner.py")],
        env=env,
        text=True,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
    )
    try:
        assert node.stderr is not None
        said, _, _ = select.select([node.stderr], [], [], 60.0)  # bounded: the note comes after 1 s
        assert said, "the node said nothing about its missing router"
        line = node.stderr.readline()
        assert "Unable to connect to the lab's Zenoh router at tcp/127.0.0.1:" in line, line
        assert node.poll() is None  # it keeps waiting, as rmw_zenoh's nodes wait for their router
    finally:
        end(node)
        node.communicate()
