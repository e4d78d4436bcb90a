"""Who may join, how fast (server/classroom/admission.py), through the real app on a manual clock:
joins and wrong codes per client address and per class (429 with Retry-After), a cap of worlds
per address, names that print on one line. Each refusal starts no world, and another client's
(or, once the wait is over, the same client's) join still works.

TestClient speaks from one address; ``FromAddress`` sets each request's client address from a
header the test sends, as each student's machine would have its own on a real network.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import httpx
import pytest
from fastapi.testclient import TestClient
from starlette.types import ASGIApp, Receive, Scope, Send
from support.app import App

from node_runtime.bus import ManualClock
from node_runtime.limits import KeyedRateLimit
from server.app import create_app
from server.classroom import ClassServer
from server.host.settings import ClassroomSettings, JoinLimits, LabSettings, Listening, Settings

CODE = "JOIN42"
ADDRESS_HEADER = b"x-test-client-address"


class FromAddress:
    """The app, with each request's client address taken from the test's header."""

    def __init__(self, app: ASGIApp) -> None:
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] in ("http", "websocket"):
            address = dict(scope["headers"]).get(ADDRESS_HEADER)
            if address is not None:
                scope = {**scope, "client": (address.decode(), 40000)}
        await self.app(scope, receive, send)


@pytest.fixture
def clock() -> ManualClock:
    return ManualClock(1_000.0)


def class_client(clock: ManualClock, **limits: Any) -> TestClient:
    settings = Settings(
        listen=Listening(allowed_hosts=("testserver",)),
        lab=LabSettings(launch="rocket", launch_args={"start_delay": "3600"}, viewer=False),
        classroom=ClassroomSettings(code=CODE, max_worlds=8, joins=JoinLimits(**limits)),
    )
    app = create_app(settings, clock)
    client = TestClient(FromAddress(app))
    client.app_state = app.state  # type: ignore[attr-defined]
    return client


def classroom(client: TestClient) -> ClassServer:
    return client.app_state.classroom  # type: ignore[attr-defined,no-any-return]


def attempt(client: TestClient, name: str, address: str, code: str = CODE) -> Any:
    reply = client.post(
        "/api/classroom/join", json={"name": name, "code": code}, headers={ADDRESS_HEADER.decode(): address}
    )
    client.cookies.clear()
    return reply


def retry_after(reply: Any) -> float:
    assert reply.status_code == 429, reply.text
    seconds = float(reply.headers["Retry-After"])
    assert seconds >= 1
    return seconds


@pytest.fixture
def guarded(clock: ManualClock) -> Iterator[TestClient]:
    with class_client(clock, wrong_codes_per_address_burst=3, wrong_codes_per_address_hz=0.1) as client:
        yield client


def test_a_wrong_code_flood_is_throttled_while_another_address_joins(
    guarded: TestClient, clock: ManualClock
) -> None:
    for i in range(3):
        assert attempt(guarded, "Eve", "10.0.0.66", code=f"GUESS{i}").status_code == 403
    flood = [attempt(guarded, "Eve", "10.0.0.66", code=f"MORE{i}") for i in range(20)]

    assert {r.status_code for r in flood} == {429}
    assert "too many wrong class codes from your address" in flood[0].json()["detail"]
    wait = retry_after(flood[-1])
    # Throttled means not compared at all: the right code from the flooding address is refused too.
    assert attempt(guarded, "Eve", "10.0.0.66").status_code == 429
    assert classroom(guarded).worlds == {}
    assert attempt(guarded, "Ada", "10.0.0.7").status_code == 201  # another address: the class is open
    clock.advance(wait)
    assert attempt(guarded, "Eve", "10.0.0.66").status_code == 201
    assert set(classroom(guarded).worlds) == {"ada", "eve"}


def test_wrong_codes_from_many_addresses_meet_the_class_limit(clock: ManualClock) -> None:
    with class_client(clock, wrong_codes_class_burst=4, wrong_codes_class_hz=0.5) as client:
        for i in range(4):
            assert attempt(client, "Eve", f"10.0.1.{i}", code="WRONG0").status_code == 403
        refused = attempt(client, "Eve", "10.0.1.99", code="WRONG0")
        assert "too many wrong class codes in this class" in refused.json()["detail"]
        clock.advance(retry_after(refused))
        assert attempt(client, "Ada", "10.0.1.100").status_code == 201


def test_joins_from_one_address_are_rate_limited_and_another_address_still_joins(clock: ManualClock) -> None:
    with class_client(clock, per_address_burst=2, per_address_hz=0.5) as client:
        assert attempt(client, "Ada", "10.0.0.5").status_code == 201
        assert attempt(client, "Bob", "10.0.0.5").status_code == 201
        refused = attempt(client, "Cy", "10.0.0.5")
        assert "too many joins from your address" in refused.json()["detail"]
        wait = retry_after(refused)
        assert set(classroom(client).worlds) == {"ada", "bob"}
        assert attempt(client, "Dee", "10.0.0.6").status_code == 201
        clock.advance(wait)
        assert attempt(client, "Cy", "10.0.0.5").status_code == 201


def test_joins_in_the_whole_class_are_rate_limited(clock: ManualClock) -> None:
    with class_client(clock, class_burst=2, class_hz=1.0) as client:
        assert attempt(client, "Ada", "10.0.0.1").status_code == 201
        assert attempt(client, "Bob", "10.0.0.2").status_code == 201
        refused = attempt(client, "Cy", "10.0.0.3")
        assert "too many joins in this class" in refused.json()["detail"]
        clock.advance(retry_after(refused))
        assert attempt(client, "Cy", "10.0.0.3").status_code == 201


def test_a_cap_of_worlds_per_address_holds_until_one_is_removed(clock: ManualClock) -> None:
    with class_client(clock, max_worlds_per_address=1) as client:
        assert attempt(client, "Ada", "10.0.0.5").status_code == 201
        refused = attempt(client, "Ada Again", "10.0.0.5")
        assert (
            refused.status_code == 429 and "at most 1 worlds per client address" in refused.json()["detail"]
        )
        assert set(classroom(client).worlds) == {"ada"}
        assert attempt(client, "Bob", "10.0.0.6").status_code == 201
        teacher = {"Authorization": f"Bearer {classroom(client).instructor_token}"}
        assert client.delete("/api/classroom/worlds/ada", headers=teacher).status_code == 200
        assert attempt(client, "Ada Again", "10.0.0.5").status_code == 201


@pytest.mark.parametrize(
    ("name", "code_point"),
    [
        ("Eve\r\n12:00:00 INFO classroom: Mallory joined: world mallory", "U+000D"),
        ("Eve\nINFO", "U+000A"),
        ("Eve\x1b[2J", "U+001B"),
        ("Eve\u202eevE", "U+202E"),  # right-to-left override (Cf)
        ("Eve\u2028Mallory", "U+2028"),  # line separator
    ],
)
def test_a_name_with_a_control_character_is_422_naming_it(
    guarded: TestClient, name: str, code_point: str
) -> None:
    refused = attempt(guarded, name, "10.0.0.9")
    assert refused.status_code == 422
    assert f"control character ({code_point}" in refused.json()["detail"]
    assert classroom(guarded).worlds == {}
    joined = attempt(guarded, "Ada Lovelace-Byron, Jr.", "10.0.0.9")
    assert joined.status_code == 201 and joined.json()["student"] == "Ada Lovelace-Byron, Jr."


def test_a_live_class_server_tells_client_addresses_apart(tmp_path: Path) -> None:
    """``--max-worlds-per-address`` and the wrong-code throttle on a real server, each client
    speaking from its own loopback address (Linux answers all of 127.0.0.0/8)."""
    app = App(
        tmp_path,
        "--classroom",
        "--class-code",
        CODE,
        "--launch",
        "rocket",
        "--no-foxglove",
        "--max-worlds-per-address",
        "1",
    )
    clients = {
        host: httpx.Client(base_url=app.url, transport=httpx.HTTPTransport(local_address=host), timeout=30)
        for host in ("127.0.0.1", "127.0.0.2", "127.0.0.3", "127.0.0.4")
    }
    try:

        def join(host: str, name: str, code: str = CODE) -> httpx.Response:
            return clients[host].post("/api/classroom/join", json={"name": name, "code": code})

        assert join("127.0.0.1", "Ada").status_code == 201
        second = join("127.0.0.1", "Al")
        assert second.status_code == 429 and "at most 1 worlds per client address" in second.json()["detail"]
        assert join("127.0.0.2", "Bob").status_code == 201
        guesses = [join("127.0.0.3", "Eve", f"GUESS{i}").status_code for i in range(6)]
        assert guesses == [403] * 5 + [429]
        throttled = join("127.0.0.3", "Eve")  # the right code, from the guessing address
        assert throttled.status_code == 429 and int(throttled.headers["Retry-After"]) >= 1
        forged = join("127.0.0.4", "Cy\r\n00:00:00 INFO classroom: Mallory joined: world mallory")
        assert forged.status_code == 422 and "U+000D" in forged.json()["detail"]
        assert join("127.0.0.4", "Cy").status_code == 201
        console = app.log_tail(100_000)
        assert "Ada joined" in console and "Cy joined" in console and "Mallory" not in console
    finally:
        for client in clients.values():
            client.close()
        app.stop()


def test_addresses_held_for_their_limits_are_bounded_and_the_oldest_forgotten(clock: ManualClock) -> None:
    limits = KeyedRateLimit(clock, rate_hz=0.1, burst=1, max_keys=3)
    assert limits["10.0.0.1"].take()
    assert not limits["10.0.0.1"].take()  # spent, while remembered
    for i in range(2, 6):
        limits[f"10.0.0.{i}"].take()
    assert len(limits) == 3
    assert limits["10.0.0.1"].take()  # forgotten first: a new key's bucket, full again
