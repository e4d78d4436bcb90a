"""The domain bridge's route table on its own: which worlds a token's coming or going marks for a
look, and each world's routes read without the others'. No Zenoh session: tokens are handed in as
the liveliness subscriber hands them."""

from __future__ import annotations

from types import SimpleNamespace

import pytest
import zenoh

from node_runtime.transport import domain_routes
from node_runtime.transport.domain_routes import BridgeStats, Route, RouteTable
from node_runtime.transport.keys import EntityKind, EntityToken, keep_last

TYPE, HASH = "std_msgs::msg::dds_::Int64_", "RIHS01_" + "ab" * 32
WORLD_ZID = "1f" * 8


def key(domain_id: int, kind: EntityKind, topic: str, entity_id: int) -> str:
    token = EntityToken(
        domain_id, WORLD_ZID, 1, entity_id, kind, "/", "sim",
        topic=topic, dds_type=TYPE, type_hash=HASH, qos=keep_last(10),
    )  # fmt: skip
    return token.key


def sample(token_key: str, alive: bool = True) -> SimpleNamespace:
    return SimpleNamespace(
        key_expr=token_key, kind=zenoh.SampleKind.PUT if alive else zenoh.SampleKind.DELETE
    )


def route(domain_id: int, kind: EntityKind, topic: str) -> Route:
    return Route(domain_id, kind, topic, TYPE, HASH)


@pytest.fixture
def table() -> RouteTable:
    return RouteTable(0, "b1" * 8, BridgeStats())


def test_a_token_marks_its_own_world_only_and_once(table: RouteTable) -> None:
    table.set_world(1, "ada")
    table.set_world(2, "bob")
    assert table.take_changed() == [1, 2]  # named: each looked at once
    assert table.take_changed() == []
    assert table.record(sample(key(2, EntityKind.PUBLISHER, "/chatter", 2)))
    assert table.record(sample(key(2, EntityKind.SUBSCRIPTION, "/chatter", 3)))
    assert table.take_changed() == [2]
    # The same token again changes nothing; a token of the class's own domain is never read.
    assert not table.record(sample(key(2, EntityKind.PUBLISHER, "/chatter", 2)))
    assert not table.record(sample(key(0, EntityKind.PUBLISHER, "/chatter", 4)))
    assert table.take_changed() == []
    assert table.record(sample(key(2, EntityKind.PUBLISHER, "/chatter", 2), alive=False))
    assert table.take_changed() == [2]
    table.drop_world(1)
    table.touch(3)
    assert table.take_changed() == [1, 3]


def test_a_worlds_routes_are_read_without_the_others(table: RouteTable) -> None:
    table.set_world(1, "ada")
    table.set_world(2, "bob")
    table.record(sample(key(1, EntityKind.PUBLISHER, "/gps", 2)))
    table.record(sample(key(1, EntityKind.SERVICE, "/reset", 3)))
    table.record(sample(key(2, EntityKind.PUBLISHER, "/gps", 4)))
    table.record(sample(key(2, EntityKind.PUBLISHER, "/gps", 5)))  # a second publisher: one route
    assert table.wanted_in(1) == (
        "/ada",
        {route(1, EntityKind.PUBLISHER, "/gps"): keep_last(10), route(1, EntityKind.SERVICE, "/reset"): keep_last(10)},
    )  # fmt: skip
    assert table.wanted_in(2) == ("/bob", {route(2, EntityKind.PUBLISHER, "/gps"): keep_last(10)})
    assert table.wanted_in(7) == (None, {})  # no world there
    # The whole class is the worlds' routes together, each under its world's name.
    assert table.wanted() == {
        route(1, EntityKind.PUBLISHER, "/gps"): ("/ada", keep_last(10)),
        route(1, EntityKind.SERVICE, "/reset"): ("/ada", keep_last(10)),
        route(2, EntityKind.PUBLISHER, "/gps"): ("/bob", keep_last(10)),
    }
    # A world's route goes with the last of its tokens; a world dropped wants nothing.
    table.record(sample(key(2, EntityKind.PUBLISHER, "/gps", 4), alive=False))
    assert table.wanted_in(2)[1] == {route(2, EntityKind.PUBLISHER, "/gps"): keep_last(10)}
    table.record(sample(key(2, EntityKind.PUBLISHER, "/gps", 5), alive=False))
    assert table.wanted_in(2) == ("/bob", {})
    table.drop_world(1)
    assert table.wanted_in(1) == (None, {})


def test_each_worlds_limits_hold_when_read_alone(table: RouteTable, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(domain_routes, "MAX_ROUTES_PER_WORLD", 2)
    monkeypatch.setattr(domain_routes, "MAX_TOKENS_PER_DOMAIN", 3)
    table.set_world(1, "ada")
    table.set_world(2, "bob")
    recorded = [table.record(sample(key(1, EntityKind.PUBLISHER, f"/t{i}", 10 + i))) for i in range(5)]
    assert recorded == [True, True, True, False, False]  # the domain's tokens read stop at 3
    assert table.record(sample(key(2, EntityKind.PUBLISHER, "/fine", 2)))  # another world's are read
    namespace, routes = table.wanted_in(1)
    assert (namespace, list(routes)) == (
        "/ada", [route(1, EntityKind.PUBLISHER, "/t0"), route(1, EntityKind.PUBLISHER, "/t1")],
    )  # fmt: skip
    assert list(table.wanted_in(2)[1]) == [route(2, EntityKind.PUBLISHER, "/fine")]
    # A token gone frees its place: the next one of that domain is read.
    table.record(sample(key(1, EntityKind.PUBLISHER, "/t0", 10), alive=False))
    assert table.record(sample(key(1, EntityKind.PUBLISHER, "/t3", 13)))
    assert list(table.wanted_in(1)[1]) == [
        route(1, EntityKind.PUBLISHER, "/t1"),
        route(1, EntityKind.PUBLISHER, "/t2"),
    ]
