"""A bounded read of a TestClient WebSocket, for tests anywhere under tests/."""

from __future__ import annotations

import queue
import threading
from typing import Any

import pytest
from starlette.testclient import WebSocketTestSession
from starlette.types import Message

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
