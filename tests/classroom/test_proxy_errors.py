"""A class server's call to a world worker that fails names what happened in its 502: the error's
own words, or its type where it has none (a connection reset, say)."""

from __future__ import annotations

import asyncio
import json
import socket
from types import SimpleNamespace
from typing import Any

import pytest

from api.middleware.world_proxy import _forward_http
from server.classroom.worker_connections import WorkerConnections
from server.classroom.workers import WorkerRef


def forwarded(port: int) -> tuple[int, str]:
    """The status and detail the class server answers for a call to a worker at ``port``."""
    sent: list[dict[str, Any]] = []

    async def receive() -> dict[str, Any]:
        return {"type": "http.request", "body": b"", "more_body": False}

    async def send(message: dict[str, Any]) -> None:
        sent.append(message)

    async def go() -> None:
        directory = SimpleNamespace(connections=WorkerConnections(30.0), class_token="class-token")
        ref = WorkerRef(
            id="local-1", url=f"http://127.0.0.1:{port}", worlds=1, max_worlds=30, token="worker-token"
        )
        scope = {
            "type": "http",
            "method": "PUT",
            "path": "/api/workspace/files/src/demo/a.py",
            "raw_path": b"/api/workspace/files/src/demo/a.py",
            "query_string": b"",
            "headers": [],
        }
        grant = SimpleNamespace(is_instructor=True)
        await _forward_http(directory, grant, SimpleNamespace(name="ada"), ref, scope, receive, send)  # type: ignore[arg-type]

    asyncio.run(go())
    start = next(m for m in sent if m["type"] == "http.response.start")
    body = b"".join(m.get("body", b"") for m in sent if m["type"] == "http.response.body")
    return start["status"], json.loads(body)["detail"]


def closed_port() -> int:
    """A loopback port nothing listens on."""
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


PREFIX = "world 'ada' runs on world worker 'local-1', which did not answer: "


def test_a_worker_nobody_listens_for_is_a_502_in_the_errors_words() -> None:
    status, detail = forwarded(closed_port())
    assert status == 502
    assert detail.startswith(PREFIX) and "Connect call failed" in detail


def test_a_reset_with_no_words_of_its_own_is_named_by_its_type(monkeypatch: pytest.MonkeyPatch) -> None:
    async def reset(*_: Any, **__: Any) -> Any:
        raise ConnectionResetError()  # as a reset reads: no text

    monkeypatch.setattr(asyncio, "open_connection", reset)
    status, detail = forwarded(closed_port())
    assert (status, detail) == (502, PREFIX + "ConnectionResetError")


def test_a_worker_that_hangs_up_before_its_answer_is_a_502_that_says_so() -> None:
    async def scenario() -> tuple[int, str]:
        async def hang_up(reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
            await reader.readuntil(b"\r\n\r\n")  # the request's head, then nothing
            writer.close()

        server = await asyncio.start_server(hang_up, "127.0.0.1", 0)
        port = server.sockets[0].getsockname()[1]
        try:
            return await asyncio.to_thread(forwarded, port)
        finally:
            server.close()

    assert asyncio.run(scenario()) == (502, PREFIX + "the worker closed the connection before it answered")
