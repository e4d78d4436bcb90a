"""A bounded read of a TestClient WebSocket, for tests anywhere under tests/."""

from __future__ import annotations

import queue
import threading
from typing import Any

import pytest
from starlette.testclient import TestClient, WebSocketTestSession
from starlette.types import Message
from starlette.websockets import WebSocketDisconnect

WAIT_S = 10.0  # generous: a loaded 2-core CI machine; a passing read returns at once


def receive_within(ws: WebSocketTestSession, timeout_s: float = WAIT_S) -> Message:
    """The next ASGI message the app sent on ``ws``; fails after ``timeout_s``.

    TestClient's ``receive`` has no timeout, so it runs in a helper thread; if the test fails
    here, closing the session ends that thread's read.
    """
    box: queue.Queue[tuple[bool, Any]] = queue.Queue(maxsize=1)

    def read() -> None:
        try:
            box.put((True, ws.receive()))
        except BaseException as exc:  # handed to the test's thread
            box.put((False, exc))

    threading.Thread(target=read, name="ws-receive", daemon=True).start()
    try:
        ok, value = box.get(timeout=timeout_s)
    except queue.Empty:
        pytest.fail(f"no WebSocket message within {timeout_s} s")
    if not ok:
        raise value
    return value


def refusal(client: TestClient, url: str, **kwargs: Any) -> WebSocketDisconnect:
    """Open ``url`` expecting the app to refuse it: accepted, then closed at once with a code
    (api/middleware/socket_refusal.py), nothing sent before the close. Returns the close as an exception."""
    with client.websocket_connect(url, **kwargs) as ws:
        message = receive_within(ws)
        if message["type"] != "websocket.close":
            pytest.fail(f"{url} was served: the app sent {message['type']} instead of a close")
        return WebSocketDisconnect(message.get("code", 1000), message.get("reason") or "")
