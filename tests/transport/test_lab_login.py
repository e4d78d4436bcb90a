"""One lab behind ``--token`` whose graph is on Zenoh: its router, like its HTTP port, lets in
only who has the lab's login, which ``GET /api/zenoh/join`` gives with the token. The router is
the app's own, on a free loopback port; the other sessions are real Zenoh clients."""

from __future__ import annotations

from collections.abc import Iterator

import pytest
import zenoh
from fastapi.testclient import TestClient
from support.app import free_port

from node_runtime.transport.acl import Credentials
from node_runtime.transport.config import ZenohSettings
from node_runtime.transport.session import build_config
from server.app import create_app
from server.host.settings import LabSettings, Listening, Settings

TOKEN = "s3cret-token"
BEARER = {"Authorization": f"Bearer {TOKEN}"}


@pytest.fixture
def lab() -> Iterator[tuple[TestClient, str]]:
    router = f"tcp/127.0.0.1:{free_port()}"
    settings = Settings(
        listen=Listening(allowed_hosts=("testserver",), token=TOKEN),
        lab=LabSettings(
            launch="rocket",
            launch_args={"start_delay": "3600"},
            viewer=False,
            zenoh=ZenohSettings(listen=(router,)),
        ),
    )
    with TestClient(create_app(settings)) as client:
        yield client, router


def open_on(router: str, login: Credentials | None) -> zenoh.Session:
    return zenoh.open(build_config(ZenohSettings(mode="client", listen=(), connect=(router,), login=login)))


def test_the_router_of_a_lab_behind_a_token_lets_in_only_its_login(lab: tuple[TestClient, str]) -> None:
    client, router = lab
    assert client.get("/api/zenoh/join").status_code == 401
    join = client.get("/api/zenoh/join", headers=BEARER).json()
    assert join["router"] == router and join["domain_id"] == 0 and join["user"] == "ros2lab-class"
    assert TOKEN not in join["password"]
    assert client.get("/api/health").json()["zenoh"]["login"] is True
    with pytest.raises(zenoh.ZError):
        open_on(router, None)
    with pytest.raises(zenoh.ZError):
        open_on(router, Credentials(join["user"], "0" * 40))
    with open_on(router, Credentials(join["user"], join["password"])) as session:
        graph = [r.ok for r in session.liveliness().get("@ros2_lv/0/**", timeout=5) if r.ok]
    assert any("countdown" in str(token.key_expr) for token in graph), [str(t.key_expr) for t in graph]


def test_a_lab_without_a_token_asks_for_no_login() -> None:
    router = f"tcp/127.0.0.1:{free_port()}"
    settings = Settings(
        listen=Listening(allowed_hosts=("testserver",)),
        lab=LabSettings(
            launch="rocket",
            launch_args={"start_delay": "3600"},
            viewer=False,
            zenoh=ZenohSettings(listen=(router,)),
        ),
    )
    with TestClient(create_app(settings)) as client:
        join = client.get("/api/zenoh/join").json()
        assert (join["user"], join["password"]) == (None, None)
        assert join["env"] == {
            "ROS_DOMAIN_ID": "0",
            "ZENOH_CONFIG_OVERRIDE": f'connect/endpoints=["{router}"]',
        }
        with open_on(router, None) as session:
            assert list(session.info.routers_zid())
