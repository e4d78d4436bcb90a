"""Every request's path is answered as sent: one that a normaliser would change is a 400 naming
what is wrong, on any route, and changes nothing; plain paths (topics with slashes, a trailing
slash, non-ASCII) pass. The proxy to a world worker refuses a URL its client would change."""

from __future__ import annotations

import pytest
from labclient import LabClient
from starlette.testclient import WebSocketDenialResponse

from api.middleware.world_proxy import PathChanged, target
from server.base.access import path_problem
from server.classroom.workers import WorkerRef

REFUSED = {
    b"/api/./topics": "dot segment",
    b"/api/x/../topics": "dot segment",
    b"/api/topics/..": "dot segment",
    b"/api/%2e/topics": "'%2e'",
    b"/api/%2E%2E/topics": "'%2E'",
    b"/api%2ftopics": "'%2f'",
    b"/api/%5Ctopics": "'%5C'",
    b"/api//topics": "empty segment",
    b"//api/topics": "empty segment",
    b"/api\\topics": "backslash",
    b"/api/\x7ftopics": "control character",
    b"api/topics": "must start with /",
    b"http://evil.example/api/topics": "must start with /",
}
PLAIN = [
    b"/",
    b"/api/topics",
    b"/api/topics/uav/sensors/gps",
    b"/api/topics/",
    b"/static/page.css",
    b"/api/types/geometry_msgs/msg/Vector3/default",
    b"/api/nodes/%C3%A9t%C3%A9",
    b"/a.b/..c/.d",
]


@pytest.mark.parametrize(("raw", "named"), REFUSED.items())
def test_a_path_a_normaliser_would_change_is_named(raw: bytes, named: str) -> None:
    problem = path_problem(raw)
    assert problem is not None and named in problem, (raw, problem)


@pytest.mark.parametrize("raw", PLAIN)
def test_a_plain_path_passes(raw: bytes) -> None:
    assert path_problem(raw) is None


@pytest.mark.parametrize("path", ["/api/%2e/topics", "/api//topics", "/api%2Ftopics", "/api/%2e%2e/health"])
def test_a_lab_refuses_a_non_canonical_path_with_400(rocket_lab: LabClient, path: str) -> None:
    reply = rocket_lab.http.get(path)
    assert reply.status_code == 400, reply.text
    assert "canonical" in reply.json()["detail"]
    assert rocket_lab.http.get("/api/topics").status_code == 200  # spelt plainly, it answers


def test_a_write_to_a_non_canonical_path_changes_nothing(rocket_lab: LabClient) -> None:
    body = {"topic": "/countdown", "msg": {"data": 3}}
    assert rocket_lab.http.post("/api//publish", json=body).status_code == 400
    assert rocket_lab.publish_count("/countdown") == 0
    assert rocket_lab.http.post("/api/publish", json=body).status_code == 200
    assert rocket_lab.publish_count("/countdown") == 1


def test_a_websocket_with_a_non_canonical_path_is_refused_with_400(rocket_lab: LabClient) -> None:
    with pytest.raises(WebSocketDenialResponse) as denied, rocket_lab.http.websocket_connect("/ws/%2e/keys"):
        pass
    assert denied.value.status_code == 400
    assert "'%2e'" in denied.value.json()["detail"]
    with rocket_lab.http.websocket_connect("/ws/keys") as ws:  # the plain path opens
        ws.send_json({"type": "keyup", "key": "ArrowUp", "code": "ArrowUp"})


def _scope(raw_path: bytes, query: bytes = b"") -> dict[str, object]:
    return {"type": "http", "path": raw_path.decode(), "raw_path": raw_path, "query_string": query}


def test_the_proxy_sends_the_path_it_checked_or_nothing() -> None:
    ref = WorkerRef("wa", "http://127.0.0.1:9", 1, 3, "secret")
    url = target(ref, _scope(b"/api/topics/uav/gps", b"world=bob&token=t&rate=2"), websocket=False)
    assert url == "http://127.0.0.1:9/api/topics/uav/gps?rate=2"  # the caller's world and token stay here
    assert target(ref, _scope(b"/ws/keys"), websocket=True) == "ws://127.0.0.1:9/ws/keys"
    for raw in (b"/api/./classroom/worlds", b"/api/x/../classroom/worlds"):
        with pytest.raises(PathChanged):  # its HTTP client would send another path than was checked
            target(ref, _scope(raw), websocket=False)
