"""One lab behind ``--token``: what an app listening beyond loopback must ask for. Every call,
page and WebSocket needs the token; the health check does not; the command line refuses to
listen beyond loopback without a token or --classroom."""

from __future__ import annotations

from collections.abc import Iterator

import pytest
from fastapi.testclient import TestClient
from support.ws import refusal

from api.errors import CloseCode
from server.__main__ import main
from server.app import create_app
from server.host.settings import LabSettings, Listening, Settings
from server.services.bridges.front import HandshakeRefused, check_handshake

TOKEN = "s3cret-token"
BEARER = {"Authorization": f"Bearer {TOKEN}"}
HOSTS = ("127.0.0.1", "testserver")
UPGRADE = {"host": "127.0.0.1:8765", "upgrade": "websocket"}


@pytest.fixture
def client() -> Iterator[TestClient]:
    settings = Settings(
        listen=Listening(allowed_hosts=("testserver",), token=TOKEN),
        lab=LabSettings(launch="rocket", launch_args={"start_delay": "3600"}, viewer=False),
    )
    with TestClient(create_app(settings)) as test_client:
        yield test_client


def test_calls_without_the_token_are_401_and_change_nothing(client: TestClient) -> None:
    assert client.get("/api/topics").status_code == 401
    publish = client.post("/api/publish", json={"topic": "/abort_takeoff", "msg": {"data": True}})
    assert publish.status_code == 401 and "token" in publish.text
    wrong = client.get("/api/topics", headers={"Authorization": "Bearer nope"})
    assert wrong.status_code == 401
    topic = client.get("/api/topics/abort_takeoff", headers=BEARER).json()
    assert topic["publish_count"] == 0 or topic["latest"]["data"] is False


def test_the_token_opens_the_api_and_the_health_check_needs_none(client: TestClient) -> None:
    assert client.get("/api/topics", headers=BEARER).status_code == 200
    assert client.get("/api/health").json()["status"] == "ok"


def test_websockets_take_the_token_as_a_header_or_query(client: TestClient) -> None:
    assert refusal(client, "/ws/keys").code == CloseCode.UNAUTHORIZED
    for url, headers in (("/ws/keys", BEARER), (f"/ws/keys?token={TOKEN}", {})):
        with client.websocket_connect(url, headers=headers) as ws:
            ws.send_json({"type": "heartbeat"})


def test_the_printed_link_sets_the_cookie_and_the_page_then_opens(client: TestClient) -> None:
    assert client.get("/").status_code == 401
    assert client.get("/", params={"token": "nope"}).status_code == 403
    link = client.get("/", params={"token": TOKEN}, follow_redirects=False)
    assert link.status_code == 303 and link.headers["location"] == "/"
    assert "httponly" in link.headers["set-cookie"].lower()
    page = client.get("/")  # with the cookie
    assert page.status_code == 200 and "/static/build/lab.js" in page.text
    assert client.get("/api/topics").status_code == 200  # the page's own calls carry the cookie


@pytest.mark.parametrize(
    ("target", "headers", "refused"),
    [
        ("/", {}, True),
        ("/?token=nope", {}, True),
        (f"/?token={TOKEN}", {}, False),
        ("/", {"authorization": f"Bearer {TOKEN}"}, False),
    ],
)
def test_a_bridge_port_asks_for_the_token_too(target: str, headers: dict[str, str], refused: bool) -> None:
    def check() -> None:
        check_handshake(f"GET {target} HTTP/1.1", {**UPGRADE, **headers}, HOSTS, (), TOKEN)

    if refused:
        with pytest.raises(HandshakeRefused) as exc:
            check()
        assert exc.value.status == 401
    else:
        check()


@pytest.mark.parametrize("host", ["0.0.0.0", "192.168.1.20", "::"])
def test_listening_beyond_loopback_without_a_login_is_refused(
    host: str, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["--host", host, "--no-zenoh"]) == 2
    err = capsys.readouterr().err
    assert f"refusing to listen on {host}" in err and "--token auto" in err and "--classroom" in err


def test_a_zenoh_router_beyond_loopback_without_a_login_is_refused(
    capsys: pytest.CaptureFixture[str],
) -> None:
    assert main(["--zenoh-listen", "tcp/0.0.0.0:7447"]) == 2
    err = capsys.readouterr().err
    assert "refusing to open the Zenoh router on tcp/0.0.0.0:7447" in err and "--token auto" in err
