"""The class server's kept connections to a world worker, against uvicorn (the server a worker
runs) in the same event loop: calls in a row share one connection and their answers arrive
whole (a body with a length, a streamed one, a request's own body); a connection idle too long,
one its worker said it closes, or one whose answer was left unread is never used again, and the
next call opens a fresh one and is answered."""

from __future__ import annotations

import asyncio
import socket
from collections.abc import AsyncIterator, Awaitable, Callable
from contextlib import asynccontextmanager
from typing import Any

import uvicorn

from node_runtime.bus import ManualClock
from server.classroom.worker_connections import MAX_IDLE_S, WorkerConnections

BIG = bytes(range(256)) * 4096  # 1 MiB, sent in 64 KiB pieces with no length
Scope = dict[str, Any]


class Worker:
    """A tiny ASGI app; notes the client port of every call (one per connection)."""

    def __init__(self) -> None:
        self.ports: list[int] = []

    async def __call__(self, scope: Scope, receive: Callable[[], Awaitable[Any]], send: Any) -> None:
        if scope["type"] != "http":
            return
        self.ports.append(scope["client"][1])
        body = b""
        while True:
            message = await receive()
            body += message.get("body", b"")
            if not message.get("more_body"):
                break
        path = scope["path"]
        if path == "/big":
            await send({"type": "http.response.start", "status": 200, "headers": []})
            for i in range(0, len(BIG), 65536):
                await send({"type": "http.response.body", "body": BIG[i : i + 65536], "more_body": True})
            await send({"type": "http.response.body", "body": b""})
            return
        headers = [(b"content-type", b"text/plain")]
        if path == "/close":
            headers.append((b"connection", b"close"))
        reply = f"{scope['method']} {path}?{scope['query_string'].decode()} {len(body)}:".encode() + body
        await send({"type": "http.response.start", "status": 201, "headers": headers})
        await send({"type": "http.response.body", "body": reply})


@asynccontextmanager
async def serving(worker: Worker) -> AsyncIterator[str]:
    sock = socket.socket()
    sock.bind(("127.0.0.1", 0))
    sock.listen()  # calls wait in its backlog until uvicorn takes them
    server = uvicorn.Server(uvicorn.Config(worker, log_level="warning", lifespan="off"))
    task = asyncio.create_task(server.serve(sockets=[sock]))
    try:
        yield f"http://127.0.0.1:{sock.getsockname()[1]}"
    finally:
        server.should_exit = True
        await task


async def call(
    connections: WorkerConnections, url: str, target: str, method: str = "GET", body: bytes = b""
) -> tuple[int, dict[bytes, bytes], bytes]:
    answer = await connections.request(method, url + target, [("x-lab-world", "ada")], body)
    try:
        data = b"".join([chunk async for chunk in answer.body()])
    finally:
        await answer.aclose()
    return answer.status, dict(answer.headers), data


def test_calls_in_a_row_share_one_kept_connection_and_every_answer_arrives_whole() -> None:
    async def scenario() -> None:
        worker = Worker()
        async with serving(worker) as url:
            connections = WorkerConnections(30.0)
            status, headers, data = await call(connections, url, "/api/nodes?a=1")
            assert (status, headers[b"content-type"], data) == (201, b"text/plain", b"GET /api/nodes?a=1 0:")
            assert (await call(connections, url, "/api/topics"))[2] == b"GET /api/topics? 0:"
            status, _, data = await call(connections, url, "/big")
            assert (status, data) == (200, BIG)
            status, _, data = await call(connections, url, "/api/run", "POST", b'{"package": "p"}')
            assert (status, data) == (201, b'POST /api/run? 16:{"package": "p"}')
            assert len(worker.ports) == 4 and len(set(worker.ports)) == 1  # one connection for all
            assert connections.opened == 1
            connections.close()

    asyncio.run(scenario())


def test_a_connection_idle_too_long_closed_by_its_worker_or_left_unread_is_not_used_again() -> None:
    async def scenario() -> None:
        worker = Worker()
        clock = ManualClock(100.0)
        async with serving(worker) as url:
            connections = WorkerConnections(30.0, clock=clock.now)
            await call(connections, url, "/one")
            clock.advance(MAX_IDLE_S / 2)
            await call(connections, url, "/two")  # kept: idle for less than its time
            assert connections.opened == 1
            clock.advance(MAX_IDLE_S + 0.1)
            assert (await call(connections, url, "/three"))[0] == 201  # too long idle: a fresh one
            assert connections.opened == 2
            await call(connections, url, "/close")  # the worker says it closes this one
            assert (await call(connections, url, "/four"))[0] == 201
            assert connections.opened == 3
            answer = await connections.request("GET", url + "/big", [], b"")
            first = await anext(answer.body())
            await answer.aclose()  # read 64 KiB of 1 MiB, then gave up
            assert first == BIG[: len(first)]
            status, _, data = await call(connections, url, "/five")
            assert (status, data) == (201, b"GET /five? 0:")
            assert connections.opened == 4
            assert len(set(worker.ports)) == 4  # each fresh connection was the worker's too
            connections.close()

    asyncio.run(scenario())
