"""Every TCP port the app's processes listen on refuses a page of another site that has no token,
and the app's WebSocket routes refuse the one way (a completed handshake closed at once with the
close code that names why): a single lab behind a token, and a class server with a world worker.

The ports are read from the system, not from the app: the listening sockets of /proc/<pid>/net/tcp
(and tcp6) whose inodes are among the sockets in /proc/<pid>/fd, for the server process and every
process it started. Each one is offered a WebSocket handshake from http://evil.example with no
token; each refuses. The same ports with the token and the page's own origin serve (the Foxglove
server its serverInfo, rosbridge a rosapi answer, the 3D view through the app's proxy), so the
refusals are the guard's and not a broken server's. And none of them deflates its frames.
"""

from __future__ import annotations

import asyncio
import json
import os
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
import viser
import websockets
from handshake import READ_S, handshake_refusal
from support.app import App, free_ports, instructor_token, wait_for_workers
from support.http import HTTP

from api.errors import CloseCode
from server.app import create_app
from server.host.settings import ClassroomSettings, LabSettings, Settings

TOKEN = "a-lab-token-for-this-test"
FOREIGN = "http://evil.example"
SUBPROTOCOLS = ("foxglove.sdk.v1", f"viser-v{viser.__version__}")
LISTEN = "0A"  # a TCP socket's state in /proc/net/tcp
# Every WebSocket route of the app, with the way a client names a world or a topic.
WS_ROUTES = (
    "/",
    "/ws/keys",
    "/ws/topics/countdown",
    "/ws/launches/run1/output",
    "/rosbridge",
    "/class/rosbridge",
    "/instructor/view",
)


def process_tree(pid: int) -> list[int]:
    """``pid`` and every process it started, and theirs."""
    found, todo = [], [pid]
    while todo:
        current = todo.pop()
        found.append(current)
        for task in Path(f"/proc/{current}/task").iterdir():
            children = (task / "children").read_text().split()
            todo.extend(int(child) for child in children)
    return found


def listening_ports(pid: int) -> set[int]:
    """The TCP ports the process ``pid`` listens on: its socket inodes, found among the LISTEN
    sockets of its network namespace."""
    inodes = set()
    for fd in Path(f"/proc/{pid}/fd").iterdir():
        try:
            target = os.readlink(fd)
        except OSError:  # closed meanwhile
            continue
        if target.startswith("socket:["):
            inodes.add(target[8:-1])
    ports = set()
    for table in ("tcp", "tcp6"):
        for line in Path(f"/proc/{pid}/net/{table}").read_text().splitlines()[1:]:
            fields = line.split()
            if fields[3] == LISTEN and fields[9] in inodes:
                ports.add(int(fields[1].rsplit(":", 1)[1], 16))
    return ports


def ports_of(app: App) -> dict[int, set[int]]:
    """Listening port → the processes holding it, over the app's process tree."""
    held: dict[int, set[int]] = {}
    for pid in process_tree(app.proc.pid):
        for port in listening_ports(pid):
            held.setdefault(port, set()).add(pid)
    return held


def foreign_refusal(port: int, path: str = "/") -> int:
    headers = (
        ("Host", f"127.0.0.1:{port}"),
        ("Origin", FOREIGN),
        ("Sec-WebSocket-Protocol", ", ".join(SUBPROTOCOLS)),
    )
    return asyncio.run(handshake_refusal(port, path, headers))


def zenoh_refuses_http(port: int) -> bool:
    """A Zenoh listener speaks Zenoh's own protocol (its logins are Zenoh's); it never completes
    an HTTP handshake: it closes the connection, or answers no HTTP."""

    async def attempt() -> bool:
        reader, writer = await asyncio.open_connection("127.0.0.1", port)
        try:
            writer.write(b"GET / HTTP/1.1\r\nHost: x\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n\r\n")
            async with asyncio.timeout(READ_S):
                answer = await reader.read(12)
            return not answer.startswith(b"HTTP/")
        except (ConnectionError, TimeoutError):
            return True
        finally:
            writer.close()

    return asyncio.run(attempt())


def check_every_port(app: App, zenoh_ports: set[int], client_ports: set[int]) -> set[int]:
    """Each listening port refuses a foreign page without a token; returns the ports seen.
    ``client_ports`` are those clients are meant to reach (the app's, Foxglove's, rosbridge's)."""
    held = ports_of(app)
    assert app.port in held, f"the app's own port {app.port} is not among {sorted(held)}: the scan is broken"
    for port in held:
        if port in zenoh_ports:
            assert zenoh_refuses_http(port), f"Zenoh's port {port} answered HTTP"
            continue
        answer = foreign_refusal(port)
        # A refused WebSocket closes with the code that says why (its Origin is refused before
        # any token is read); only viser's own ports, which the app's proxy alone reaches with
        # its secret, answer the handshake with HTTP 403.
        assert answer == CloseCode.FORBIDDEN or (answer == 403 and port not in client_ports), (port, answer)
    return set(held)


def app_routes_refuse_a_foreign_page(port: int) -> None:
    for path in WS_ROUTES:
        assert foreign_refusal(port, path) == CloseCode.FORBIDDEN, path


# -- what the guarded ports serve to the right client ------------------------------------------
async def _first_text(url: str, origin: str, subprotocol: str | None = None, send: str | None = None) -> Any:
    protocols = [websockets.Subprotocol(subprotocol)] if subprotocol else None
    async with websockets.connect(url, origin=websockets.Origin(origin), subprotocols=protocols) as ws:
        if send is not None:
            await ws.send(send)
        async with asyncio.timeout(READ_S):
            frame = await ws.recv()
    return json.loads(frame) if isinstance(frame, str) else frame


def serves_foxglove(port: int, token: str) -> bool:
    url = f"ws://127.0.0.1:{port}/?token={token}"
    info = asyncio.run(_first_text(url, f"http://127.0.0.1:{port}", "foxglove.sdk.v1"))
    return bool(info["op"] == "serverInfo")


def serves_rosbridge(port: int, path: str, token: str) -> bool:
    call = json.dumps({"op": "call_service", "id": "t", "service": "/rosapi/get_time"})
    url = f"ws://127.0.0.1:{port}{path}?token={token}"
    reply = asyncio.run(_first_text(url, f"http://127.0.0.1:{port}", send=call))
    return bool(reply["id"] == "t" and reply["result"] is True)


def serves_the_view(port: int, token: str) -> bool:
    """The 3D view through the app's proxy: viser's first message, msgpack bytes."""
    url = f"ws://127.0.0.1:{port}/?token={token}"
    first = asyncio.run(_first_text(url, f"http://127.0.0.1:{port}", f"viser-v{viser.__version__}"))
    return isinstance(first, bytes) and len(first) > 0


async def _extensions(url: str, origin: str, subprotocol: str | None = None) -> tuple[str, str | None]:
    """What a client offering permessage-deflate asked for, and what the server agreed to."""
    protocols = [websockets.Subprotocol(subprotocol)] if subprotocol else None
    async with websockets.connect(
        url, origin=websockets.Origin(origin), subprotocols=protocols, compression="deflate"
    ) as ws:
        assert ws.request is not None and ws.response is not None
        return ws.request.headers["Sec-WebSocket-Extensions"], ws.response.headers.get(
            "Sec-WebSocket-Extensions"
        )


def assert_no_compression(port: int, path: str, token: str, subprotocol: str | None = None) -> None:
    """The WebSocket at ``path`` sends its frames as they are, to a client that offers to deflate."""
    url = f"ws://127.0.0.1:{port}{path}{'&' if '?' in path else '?'}token={token}"
    offered, agreed = asyncio.run(_extensions(url, f"http://127.0.0.1:{port}", subprotocol))
    assert offered.startswith("permessage-deflate"), offered
    assert agreed is None, (path, agreed)


def test_the_route_list_is_every_websocket_route_of_the_app() -> None:
    from starlette.routing import WebSocketRoute

    for settings in (
        Settings(lab=LabSettings(viewer=False)),
        Settings(lab=LabSettings(viewer=False), classroom=ClassroomSettings()),
    ):
        routes = set()
        for route in create_app(settings).routes:
            for context in getattr(route, "effective_route_contexts", list)():  # FastAPI's included routers
                if isinstance(context.original_route, WebSocketRoute):
                    routes.add(context.frontend_prefix + context.original_route.path)
        named = {r.replace("countdown", "{name:path}").replace("run1", "{group_id}") for r in WS_ROUTES}
        assert routes == named


# -- a single lab ---------------------------------------------------------------------------
@pytest.fixture(scope="module")
def lab(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[App, int, int]]:
    foxglove, rosbridge = free_ports(2)
    app = App(
        tmp_path_factory.mktemp("every_port_lab"),
        "--launch",
        "rocket",
        "start_delay:=3600",
        "--token",
        TOKEN,
        "--foxglove-port",
        str(foxglove),
        "--rosbridge-port",
        str(rosbridge),
    )
    try:
        yield app, foxglove, rosbridge
    finally:
        app.stop()


def test_every_port_of_a_single_lab_refuses_a_foreign_page(lab: tuple[App, int, int]) -> None:
    app, foxglove, rosbridge = lab
    seen = check_every_port(app, {app.zenoh_port}, {app.port, foxglove, rosbridge})
    assert {app.port, foxglove, rosbridge, app.zenoh_port} <= seen
    assert len(seen) == 5, f"expected the app, viser, Foxglove, rosbridge and Zenoh ports: {sorted(seen)}"
    app_routes_refuse_a_foreign_page(app.port)
    # Without the token, from the page's own origin: refused for want of it.
    own = (("Host", f"127.0.0.1:{foxglove}"), ("Origin", f"http://127.0.0.1:{foxglove}"))
    assert asyncio.run(handshake_refusal(foxglove, "/", own)) == CloseCode.UNAUTHORIZED
    # With it: served.
    assert serves_foxglove(foxglove, TOKEN)
    assert serves_rosbridge(rosbridge, "/", TOKEN)
    assert serves_rosbridge(app.port, "/rosbridge", TOKEN)
    assert serves_the_view(app.port, TOKEN)


def test_no_websocket_of_a_lab_deflates_its_frames(lab: tuple[App, int, int]) -> None:
    """Deflating each frame on its own took about 30 % of what a 100 Hz pose stream cost, and
    viser's frames are compressed already: every WebSocket the lab serves declines the offer."""
    app, foxglove, rosbridge = lab
    assert_no_compression(app.port, "/ws/topics/countdown", TOKEN)
    assert_no_compression(app.port, "/ws/keys", TOKEN)
    assert_no_compression(app.port, "/rosbridge", TOKEN)
    assert_no_compression(app.port, "/", TOKEN, f"viser-v{viser.__version__}")
    assert_no_compression(foxglove, "/", TOKEN, "foxglove.sdk.v1")
    assert_no_compression(rosbridge, "/", TOKEN)


# -- a class server with a world worker -----------------------------------------------------
@pytest.fixture(scope="module")
def school(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[App, int, int, str]]:
    foxglove, rosbridge = free_ports(2)
    app = App(
        tmp_path_factory.mktemp("every_port_class"),
        "--classroom",
        "--class-code",
        "PORTS1",
        "--launch",
        "fly",
        "--workers",
        "1",
        "--local-worlds",
        "1",
        "--foxglove-port",
        str(foxglove),
        "--rosbridge-port",
        str(rosbridge),
    )
    try:
        instructor = instructor_token(app.log_tail(10**6))
        wait_for_workers(app.url, instructor, {"local-1"})
        for name in ("Ada", "Bob"):  # one world here, one on the worker
            reply = HTTP.post(
                f"{app.url}/api/classroom/join", json={"name": name, "code": "PORTS1"}, timeout=60
            )
            assert reply.status_code == 201, reply.text
        yield app, foxglove, rosbridge, instructor
    finally:
        app.stop()


def test_every_port_of_a_class_and_its_world_worker_refuses_a_foreign_page(
    school: tuple[App, int, int, str],
) -> None:
    app, foxglove, rosbridge, instructor = school
    workers = HTTP.get(f"{app.url}/api/classroom/workers", headers={"Authorization": f"Bearer {instructor}"})
    worker_port = int(workers.json()["workers"][0]["url"].rsplit(":", 1)[1])
    seen = check_every_port(app, {app.zenoh_port}, {app.port, foxglove, rosbridge, worker_port})
    assert {app.port, foxglove, rosbridge, worker_port} <= seen
    for port in (app.port, worker_port):
        app_routes_refuse_a_foreign_page(port)
    assert serves_foxglove(foxglove, instructor)
    assert serves_rosbridge(rosbridge, "/", instructor)
    assert serves_rosbridge(app.port, "/class/rosbridge", instructor)
