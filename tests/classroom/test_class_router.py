"""The class's router on its own (server/classroom/class_router.py): a login per world domain,
random, and revoked by opening the router again, which drops that login's sessions and no
other's for good. Real Zenoh sessions on loopback, multicast scouting off."""

from __future__ import annotations

import asyncio
from typing import Any

import pytest
import zenoh
from fastapi.testclient import TestClient
from support.app import free_port
from support.wait import wait_until

from node_runtime.transport.acl import ClassAuth, Credentials, new_world_login
from node_runtime.transport.config import ZenohSettings
from node_runtime.transport.session import build_config
from server.app import create_app
from server.classroom import ClassServer
from server.classroom.class_router import ClassRouter
from server.classroom.workers import worker_api_token
from server.host.settings import ClassroomSettings, LabSettings, Listening, Settings, WorkerSettings


def client(endpoint: str, login: Credentials) -> Any:
    return zenoh.open(build_config(ZenohSettings(mode="client", listen=(), connect=(endpoint,), login=login)))


def test_a_domains_login_is_random_and_the_class_domain_has_none() -> None:
    settings = ZenohSettings(mode="router", listen=(f"tcp/127.0.0.1:{free_port()}",), domain_id=5)
    one, other = (ClassRouter(settings, ClassAuth("t").class_credentials()) for _ in range(2))
    assert one.login(1) != other.login(1) and one.login(1) != one.login(2)
    assert one.login(1).user.startswith("ros2lab-world-1-")
    with pytest.raises(ValueError):
        one.login(5)  # the class's own domain holds no world
    assert 5 not in one.access().worlds and len(one.access().worlds) == 231


def test_revoking_a_login_drops_its_sessions_refuses_it_and_keeps_the_others() -> None:
    endpoint = f"tcp/127.0.0.1:{free_port()}"
    router = ClassRouter(ZenohSettings(mode="router", listen=(endpoint,)), ClassAuth("t").class_credentials())
    asyncio.run(router.open())
    try:
        old, stays = router.login(3), router.login(4)
        heard: list[str] = []
        with client(endpoint, old) as removed, client(endpoint, stays) as kept:
            kept.declare_subscriber("4/**", lambda sample: heard.append(str(sample.key_expr)))
            assert removed.info.routers_zid() and kept.info.routers_zid()
            asyncio.run(router.revoke([3]))
            assert router.reopened == 1 and router.login(3) != old and router.login(4) == stays
            wait_until(lambda: not removed.info.routers_zid(), "the old login's session dropped")
            with pytest.raises(zenoh.ZError):
                client(endpoint, old).close()
            with client(endpoint, router.login(3)) as fresh:  # the domain's new login works
                assert fresh.info.routers_zid()
            # The other world's session comes back by itself, its subscription with it.
            wait_until(lambda: bool(kept.info.routers_zid()), "the other login's session back")

            def heard_again() -> bool:
                router.session.put("4/marker", b"x")
                return "4/marker" in heard

            wait_until(heard_again, "the other session hearing its domain again")
            assert not removed.info.routers_zid()  # and the old one never got back in
    finally:
        router.close()


def test_a_world_worker_keeps_the_login_its_class_server_drew_for_a_world() -> None:
    settings = Settings(
        listen=Listening(allowed_hosts=("testserver",)),
        lab=LabSettings(launch="rocket", launch_args={"start_delay": "3600"}, viewer=False),
        classroom=ClassroomSettings(max_worlds=2),
        worker=WorkerSettings(
            id="wm", url="http://127.0.0.1:1", class_token="class-token", orphan_timeout_s=60.0
        ),
    )
    login = new_world_login(3)
    body = {"world": "ada", "student": "Ada", "domain_id": 3, "launch": "rocket", "launch_args": {}}
    auth = {"Authorization": f"Bearer {worker_api_token('class-token', 'wm')}"}
    with TestClient(create_app(settings)) as client:
        classroom: ClassServer = client.app.state.classroom  # type: ignore[attr-defined]
        half = client.post("/api/classroom/host", json={**body, "zenoh_user": login.user}, headers=auth)
        assert half.status_code == 422 and "come together" in half.text
        assert classroom.worlds == {}
        whole = {**body, "zenoh_user": login.user, "zenoh_password": login.password}
        reply = client.post("/api/classroom/host", json=whole, headers=auth)
        assert reply.status_code == 201, reply.text
        assert classroom.worlds["ada"].login == login  # what its resets start the world with again
        assert login.password not in reply.text
