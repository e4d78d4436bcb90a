"""A class server's call to a world worker that fails without a message (a connection reset,
say) still names what happened in its 502: the error's type stands in for its empty text."""

from __future__ import annotations

import asyncio
import json
from types import SimpleNamespace
from typing import Any

import httpx
import pytest

from api.middleware.world_proxy import _forward_http
from server.classroom.workers import WorkerRef


def forwarded(error: httpx.HTTPError) -> tuple[int, str]:
    """The status and detail the class server answers when the worker's call raises ``error``."""

    def fail(request: httpx.Request) -> httpx.Response:
        raise error

    sent: list[dict[str, Any]] = []

    async def receive() -> dict[str, Any]:
        return {"type": "http.request", "body": b"", "more_body": False}

    async def send(message: dict[str, Any]) -> None:
        sent.append(message)

    async def go() -> None:
        async with httpx.AsyncClient(transport=httpx.MockTransport(fail)) as http:
            directory = SimpleNamespace(http=http, class_token="class-token")
            ref = WorkerRef(
                id="local-1", url="http://127.0.0.1:9", worlds=1, max_worlds=30, token="worker-token"
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


@pytest.mark.parametrize(
    ("error", "named"),
    [
        (httpx.ReadError(""), "ReadError"),  # a reset: no text of its own
        (httpx.ConnectError("All connection attempts failed"), "All connection attempts failed"),
    ],
    ids=["no message", "a message"],
)
def test_a_worker_that_did_not_answer_is_a_502_that_says_how(error: httpx.HTTPError, named: str) -> None:
    status, detail = forwarded(error)
    assert status == 502
    assert detail == f"world 'ada' runs on world worker 'local-1', which did not answer: {named}"
