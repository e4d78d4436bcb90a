"""The real app behind a TestClient, with the bounded waits its API tests need.

The lab runs on the system clock in TestClient's event-loop thread, so a test cannot step time:
it looks again a little later until the condition holds or a deadline passes, and a WebSocket
read gives up after a deadline instead of blocking the run forever.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from typing import Any

from fastapi.testclient import TestClient
from starlette.testclient import WebSocketTestSession
from starlette.websockets import WebSocketDisconnect
from support.wait import wait_until
from support.ws import receive_within, refusal

from server.host.settings import LabLimits, LabSettings, Listening, Settings

WAIT_S = 10.0  # generous: a loaded 2-core CI machine; a passing test returns as soon as it can
QUIET_START_DELAY = "3600"  # the countdown never starts while the test runs


def rocket_settings(start_delay: str = QUIET_START_DELAY, **overrides: Any) -> Settings:
    """The rocket launch without viser, reachable as TestClient's Host 'testserver'; each of
    ``overrides`` is a field of the lab's section (``LabSettings``: ``viewer``, ``bag_dir``,
    ``launch``...) or of its limits (``LabLimits``)."""
    lab = {k: v for k, v in overrides.items() if k in LabSettings.model_fields}
    limits = {k: v for k, v in overrides.items() if k not in lab}
    return Settings(
        listen=Listening(allowed_hosts=("testserver",)),
        lab=LabSettings(
            **{"launch": "rocket", "launch_args": {"start_delay": start_delay}, "viewer": False, **lab}
        ),
        limits=LabLimits(**limits),
    )


class LabClient:
    """A TestClient (lifespan entered) plus topic look-ups by name."""

    def __init__(self, http: TestClient) -> None:
        self.http = http

    def topic(self, name: str) -> dict[str, Any]:
        response = self.http.get(f"/api/topics/{name.lstrip('/')}")
        assert response.status_code == 200, response.text
        return response.json()

    def latest(self, name: str) -> dict[str, Any] | None:
        return self.topic(name)["latest"]

    def publish_count(self, name: str) -> int:
        return self.topic(name)["publish_count"]

    def topic_names(self) -> set[str]:
        return {t["name"] for t in self.http.get("/api/topics", params={"hidden": True}).json()}

    def wait_latest(
        self, name: str, done: Callable[[dict[str, Any]], bool], what: str, timeout_s: float = WAIT_S
    ) -> dict[str, Any]:
        """Wait until topic ``name`` has a latest message for which ``done`` holds; return it."""

        def check() -> dict[str, Any] | None:
            latest = self.latest(name)
            return latest if latest is not None and done(latest) else None

        return wait_until(check, f"{name} {what}", timeout_s)

    def publish(self, topic: str, msg: dict[str, Any], type_name: str | None = None) -> dict[str, Any]:
        body: dict[str, Any] = {"topic": topic, "msg": msg}
        if type_name is not None:
            body["type"] = type_name
        response = self.http.post("/api/publish", json=body)
        assert response.status_code == 200, response.text
        return response.json()

    def healthy(self) -> bool:
        response = self.http.get("/api/health")
        return response.status_code == 200 and response.json()["status"] == "ok"


def receive_json_within(ws: WebSocketTestSession, timeout_s: float = WAIT_S) -> Any:
    """The next JSON text frame; a close raises WebSocketDisconnect (with its code and reason)."""
    message = receive_within(ws, timeout_s)
    if message["type"] == "websocket.close":
        raise WebSocketDisconnect(message.get("code", 1000), message.get("reason", ""))
    assert message.get("text") is not None, f"expected a text frame, got {message!r}"
    return json.loads(message["text"])


def close_within(ws: WebSocketTestSession, timeout_s: float = WAIT_S) -> tuple[int, str]:
    """Expect the server to close ``ws`` next; returns (code, reason)."""
    message = receive_within(ws, timeout_s)
    assert message["type"] == "websocket.close", f"expected a close, got {message!r}"
    return int(message.get("code", 1000)), str(message.get("reason", ""))


def refused(client: TestClient, url: str, **kwargs: Any) -> WebSocketDisconnect:
    """Open ``url`` expecting the server to refuse it (accepted, then closed at once with a code);
    returns the refusal."""
    return refusal(client, url, **kwargs)
