"""Safe by default: another site's page may not publish, reset or open a WebSocket, and a Host
that is not a name of this machine (DNS rebinding) is refused outright."""

from __future__ import annotations

import pytest
from labclient import LabClient, refused

from api.errors import CloseCode

CROSS_SITE = ["http://evil.example", "null", "http://testserver.evil.example", "http://127.0.0.1:9999"]
FOREIGN_HOSTS = ["evil.example", "localhost.evil.example", "192.168.1.10:8000", "testserver.evil.example"]
LOOPBACK_HOSTS = ["localhost:8000", "127.0.0.1:8000", "[::1]:8000", "testserver"]
WEBSOCKETS = ["/ws/keys", "/ws/topics/countdown"]


def _launched_nodes(lab: LabClient) -> list[int]:
    return [id(e.node) for e in lab.http.app.state.lab.launcher.launched]  # type: ignore[attr-defined]


@pytest.mark.parametrize("origin", CROSS_SITE)
@pytest.mark.parametrize("url", WEBSOCKETS)
def test_websocket_cross_site_origin_refused(rocket_lab: LabClient, url: str, origin: str) -> None:
    refusal = refused(rocket_lab.http, url, headers={"origin": origin})

    assert refusal.code == CloseCode.FORBIDDEN
    assert "cross-site origin" in refusal.reason


@pytest.mark.parametrize("origin", CROSS_SITE)
def test_publish_cross_site_origin_refused_and_publishes_nothing(rocket_lab: LabClient, origin: str) -> None:
    response = rocket_lab.http.post(
        "/api/publish", json={"topic": "/countdown", "msg": {"data": 3}}, headers={"origin": origin}
    )

    assert response.status_code == 403
    assert "cross-site origin" in response.json()["detail"]
    assert rocket_lab.publish_count("/countdown") == 0


def test_reset_cross_site_origin_refused_and_restarts_nothing(rocket_lab: LabClient) -> None:
    nodes_before = _launched_nodes(rocket_lab)

    response = rocket_lab.http.post("/api/rocket/reset", headers={"origin": "http://evil.example"})

    assert response.status_code == 403
    assert _launched_nodes(rocket_lab) == nodes_before


def test_publish_same_origin_accepted(rocket_lab: LabClient) -> None:
    response = rocket_lab.http.post(
        "/api/publish",
        json={"topic": "/countdown", "msg": {"data": 3}},
        headers={"origin": "http://testserver"},
    )

    assert response.status_code == 200
    assert rocket_lab.latest("/countdown") == {"data": 3}


@pytest.mark.parametrize("host", FOREIGN_HOSTS)
def test_foreign_host_refused_421_on_reads_and_writes(rocket_lab: LabClient, host: str) -> None:
    health = rocket_lab.http.get("/api/health", headers={"host": host})
    publish = rocket_lab.http.post(
        "/api/publish", json={"topic": "/countdown", "msg": {"data": 3}}, headers={"host": host}
    )

    assert (health.status_code, publish.status_code) == (421, 421)
    assert host in health.json()["detail"]
    assert rocket_lab.publish_count("/countdown") == 0


@pytest.mark.parametrize("host", FOREIGN_HOSTS)
def test_websocket_foreign_host_refused(rocket_lab: LabClient, host: str) -> None:
    refusal = refused(rocket_lab.http, "/ws/keys", headers={"host": host})

    assert refusal.code == CloseCode.MISDIRECTED
    assert host in refusal.reason


@pytest.mark.parametrize("host", LOOPBACK_HOSTS)
def test_loopback_host_accepted(rocket_lab: LabClient, host: str) -> None:
    assert rocket_lab.http.get("/api/health", headers={"host": host}).status_code == 200
