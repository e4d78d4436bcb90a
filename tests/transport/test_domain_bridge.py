"""The domain bridge's rules, with real Zenoh sessions on loopback: a router holding the bridge, a
"world" session in domain 1 that declares rmw_zenoh tokens and data, and a watcher in the class's
domain 0. Zenoh delivers on its own threads, so each wait is bounded."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import pytest
import zenoh
from support.app import free_port
from support.wait import wait_until

from node_runtime.transport import domain_bridge, domain_crossing, domain_routes
from node_runtime.transport.attachment import Attachment
from node_runtime.transport.config import ZenohSettings
from node_runtime.transport.domain_bridge import DomainBridge
from node_runtime.transport.keys import EntityKind, EntityToken, data_key, keep_last
from node_runtime.transport.session import open_session

WAIT_S = 5.0
TYPE, HASH = "std_msgs::msg::dds_::Int64_", "RIHS01_" + "ab" * 32
GID = bytes(range(16))


@dataclass
class Net:
    router: Any
    bridge: DomainBridge
    world: Any  # a session in world domain 1
    watcher: Any  # a session in the class's domain 0
    world_zid: str

    def declare(self, kind: EntityKind, topic: str, entity_id: int, domain_id: int = 1) -> Any:
        token = EntityToken(
            domain_id, self.world_zid, 1, entity_id, kind, "/", "sim",
            topic=topic, dds_type=TYPE, type_hash=HASH, qos=keep_last(10),
        )  # fmt: skip
        return self.world.liveliness().declare_token(token.key)

    def class_tokens(self) -> list[str]:
        replies = self.watcher.liveliness().get("@ros2_lv/0/**", timeout=2)
        return sorted(str(r.ok.key_expr) for r in replies if r.ok)


@pytest.fixture
def net() -> Iterator[Net]:
    endpoint = f"tcp/127.0.0.1:{free_port()}"
    router = open_session(ZenohSettings(mode="router", listen=(endpoint,), connect=()))
    client = ZenohSettings(mode="client", listen=(), connect=(endpoint,))
    world, watcher = open_session(client), open_session(client)
    bridge = DomainBridge(router, 0)
    try:
        yield Net(router, bridge, world, watcher, str(world.zid()))
    finally:
        bridge.close()
        for session in (watcher, world, router):
            session.close()


def test_a_world_shows_only_once_named_and_leaves_when_dropped(net: Net) -> None:
    keep = net.declare(EntityKind.PUBLISHER, "/chatter", 2)
    # A marker: a named world's token, declared after the unnamed one by the same session, so the
    # bridge hears it second. Once the marker is bridged, the unnamed world has been heard, and
    # shows nothing.
    net.bridge.set_world(2, "marker")
    marker = net.declare(EntityKind.PUBLISHER, "/chatter", 3, domain_id=2)
    wait_until(lambda: net.bridge.routes() != {}, "the marker world's /chatter bridged")
    assert net.bridge.routes() == {"marker": ["out /marker/chatter"]}
    marker.undeclare()
    net.bridge.drop_world(2)
    wait_until(lambda: net.bridge.routes() == {}, "the marker gone")
    net.bridge.set_world(1, "ada")
    wait_until(lambda: net.bridge.routes() == {"ada": ["out /ada/chatter"]}, "ada's /chatter bridged")
    tokens = net.class_tokens()
    assert any(t.endswith("/NN/%/%ada/domain_bridge") for t in tokens), tokens
    assert any("/MP/%/%ada/domain_bridge/%ada%chatter/" in t for t in tokens), tokens
    net.bridge.set_world(1, "bea")  # the domain taken by another world: renamed, not both
    wait_until(lambda: net.bridge.routes() == {"bea": ["out /bea/chatter"]}, "the domain under its new name")
    net.bridge.drop_world(1)
    wait_until(lambda: net.bridge.routes() == {}, "nothing bridged once the world is gone")
    wait_until(lambda: net.class_tokens() == [], "the class domain's graph empty again")
    keep.undeclare()


def test_samples_cross_while_watched_with_the_bridges_attachment_and_never_loop(net: Net) -> None:
    net.bridge.set_world(1, "ada")
    keep = [
        net.declare(EntityKind.PUBLISHER, "/chatter", 2),
        net.declare(EntityKind.SUBSCRIPTION, "/chatter", 3),
    ]
    wait_until(lambda: len(net.bridge.routes().get("ada", [])) == 2, "both ways of /chatter bridged")
    # REMOTE, as a world's bus publishes: its own process hears it on the bus, not through Zenoh.
    world_pub = net.world.declare_publisher(
        data_key(1, "/chatter", TYPE, HASH), allowed_destination=zenoh.Locality.REMOTE
    )
    assert not world_pub.matching_status.matching  # nobody watches: the world is not even asked
    out: list[tuple[bytes, Attachment | None]] = []
    back: list[bytes] = []
    watcher_sub = net.watcher.declare_subscriber(
        data_key(0, "/ada/chatter", TYPE, HASH),
        lambda s: out.append((s.payload.to_bytes(), Attachment.unpack(s.attachment.to_bytes()) if s.attachment else None)),
    )  # fmt: skip
    world_sub = net.world.declare_subscriber(
        data_key(1, "/chatter", TYPE, HASH), lambda s: back.append(s.payload.to_bytes())
    )
    wait_until(lambda: world_pub.matching_status.matching, "the bridge subscribing in the world once watched")
    assert "out* /ada/chatter" in net.bridge.routes()["ada"]
    world_pub.put(b"no attachment")  # rmw_zenoh drops it; so does the bridge
    for seq in (1, 2, 3):
        world_pub.put(b"sample %d" % seq, attachment=Attachment(seq, 1000 + seq, GID).pack())
    wait_until(lambda: len(out) == 3, "three samples in the class domain")
    assert [payload for payload, _ in out] == [b"sample 1", b"sample 2", b"sample 3"]
    attachments = [a for _, a in out]
    assert all(a is not None for a in attachments)
    assert [a.sequence_number for a in attachments if a] == [1, 2, 3]
    assert [a.source_timestamp_ns for a in attachments if a] == [1001, 1002, 1003]  # the source's time
    assert {a.gid for a in attachments if a} != {GID}  # the bridge's own publisher, as a ROS bridge is
    assert net.bridge.stats.dropped == 1
    # What crossed out is not sent back in: an echo would reach the world before this sample from
    # the class domain, which takes the same way from the router to the world after it.
    class_pub = net.watcher.declare_publisher(
        data_key(0, "/ada/chatter", TYPE, HASH), allowed_destination=zenoh.Locality.REMOTE
    )
    class_pub.put(b"from the class", attachment=Attachment(1, 5, GID).pack())
    wait_until(lambda: b"from the class" in back, "the class's sample in the world")
    assert back == [b"from the class"]
    # And into the world once, and not echoed back out: markers after it, one each way, come next.
    class_pub.put(b"class marker", attachment=Attachment(2, 6, GID).pack())
    wait_until(lambda: b"class marker" in back, "the class's marker in the world")
    world_pub.put(b"world marker", attachment=Attachment(4, 1004, GID).pack())
    wait_until(lambda: len(out) >= 4, "the world's marker in the class domain")
    assert back == [b"from the class", b"class marker"]
    assert [payload for payload, _ in out] == [b"sample 1", b"sample 2", b"sample 3", b"world marker"]
    watcher_sub.undeclare()
    wait_until(lambda: not world_pub.matching_status.matching, "the bridge leaving the world once unwatched")
    for entity in (class_pub, world_sub, world_pub, *keep):
        entity.undeclare()


def test_what_one_world_can_make_the_bridge_declare_is_bounded(
    net: Net, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(domain_routes, "MAX_ROUTES_PER_WORLD", 3)
    monkeypatch.setattr(domain_routes, "MAX_TOKENS_PER_DOMAIN", 5)
    net.bridge.set_world(1, "ada")
    net.bridge.set_world(2, "bob")
    keep = [net.declare(EntityKind.PUBLISHER, f"/flood{i}", 10 + i) for i in range(8)]
    keep.append(net.declare(EntityKind.PUBLISHER, "/fine", 2, domain_id=2))
    wait_until(lambda: len(net.bridge.routes().get("ada", [])) == 3, "ada's first three topics")
    wait_until(
        lambda: net.bridge.routes().get("bob") == ["out /bob/fine"], "bob's topic, untouched by ada's flood"
    )
    # bob's token was declared after all of ada's by the same session: with it bridged, the bridge
    # has heard every one of ada's, and still bridges only three.
    assert len(net.bridge.routes()["ada"]) == 3
    for token in keep:
        token.undeclare()
    wait_until(lambda: net.bridge.routes() == {}, "the flood gone with its tokens")


def test_the_class_domain_itself_is_never_bridged(net: Net) -> None:
    with pytest.raises(ValueError, match="class's own domain"):
        net.bridge.set_world(0, "ada")
    net.bridge.set_world(1, "ada")
    keep = net.declare(EntityKind.PUBLISHER, "/in_class", 2, domain_id=0)
    mark = net.declare(EntityKind.PUBLISHER, "/marker", 3)
    wait_until(lambda: net.bridge.routes() == {"ada": ["out /ada/marker"]}, "the world's marker bridged")
    assert "/in_class" not in str(net.bridge.routes())
    keep.undeclare()
    mark.undeclare()


def test_a_call_in_the_class_domain_is_answered_by_the_worlds_server_as_rmw_zenoh_matches_it(
    net: Net, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(domain_crossing, "MAX_CALLS_PER_WORLD", 1)
    net.bridge.set_world(1, "ada")
    token = net.declare(EntityKind.SERVICE, "/double", 2)
    held: list[Any] = []  # calls the world's server has not answered yet
    seen: list[Attachment | None] = []

    def serve(query: Any) -> None:  # as rmw_zenoh's server: echo the request's sequence number and GID
        request = Attachment.unpack(query.attachment.to_bytes() if query.attachment else None)
        seen.append(request)
        if query.payload.to_bytes() == b"hold":
            held.append(query)
            return
        assert request is not None
        answer = str(2 * int(query.payload.to_bytes())).encode()
        query.reply(
            query.key_expr, answer, attachment=Attachment(request.sequence_number, 77, request.gid).pack()
        )
        query.drop()

    server = net.world.declare_queryable(data_key(1, "/double", TYPE, HASH), serve, complete=True)
    wait_until(lambda: net.bridge.routes() == {"ada": ["srv /ada/double"]}, "ada's service bridged")
    assert any("/SS/%/%ada/domain_bridge/%ada%double/" in t for t in net.class_tokens())

    def call(payload: bytes, attachment: bytes | None) -> list[Any]:
        replies = net.watcher.get(
            data_key(0, "/ada/double", TYPE, HASH), payload=payload, attachment=attachment,
            target=zenoh.QueryTarget.ALL_COMPLETE, consolidation=zenoh.ConsolidationMode.NONE, timeout=WAIT_S,
        )  # fmt: skip
        return list(replies)

    replies = call(b"21", Attachment(41, 5, GID).pack())
    assert [r.ok.payload.to_bytes() for r in replies if r.ok] == [b"42"]
    answer = Attachment.unpack(replies[0].ok.attachment.to_bytes())
    # The caller's own sequence number and GID, so its client takes the reply; the server's time.
    assert answer == Attachment(41, 77, GID)
    request = seen[-1]
    assert request is not None and request.source_timestamp_ns == 5  # the caller's time, onward
    assert request.gid != GID  # the bridge's own client in the world
    # Without rmw_zenoh's attachment: refused, never put to the world.
    refused = call(b"1", None)
    assert [r.ok for r in refused] == [None] and b"attachment" in refused[0].err.payload.to_bytes()
    # A pattern would call every world's servers at once: refused, never put to a world.
    pattern = list(
        net.watcher.get("0/ada/**", payload=b"1", attachment=Attachment(42, 5, GID).pack(), timeout=WAIT_S)
    )
    assert [r.ok for r in pattern] == [None] and b"not a pattern" in pattern[0].err.payload.to_bytes()
    assert len(seen) == 1
    # One call may wait on the world at once here; the next is refused until it is answered.
    waiting = net.watcher.get(
        data_key(0, "/ada/double", TYPE, HASH), payload=b"hold", attachment=Attachment(50, 5, GID).pack(),
        target=zenoh.QueryTarget.ALL_COMPLETE, consolidation=zenoh.ConsolidationMode.NONE, timeout=WAIT_S,
    )  # fmt: skip
    wait_until(lambda: len(held) == 1, "the held call at the world's server")
    busy = call(b"3", Attachment(51, 5, GID).pack())
    assert [r.ok for r in busy] == [None] and b"calls are waiting on /ada" in busy[0].err.payload.to_bytes()
    first = held.pop()
    first.reply(first.key_expr, b"late", attachment=Attachment(1, 78, GID).pack())
    first.drop()
    assert [r.ok.payload.to_bytes() for r in waiting if r.ok] == [b"late"]
    assert [r.ok.payload.to_bytes() for r in call(b"4", Attachment(52, 5, GID).pack()) if r.ok] == [b"8"]
    assert (net.bridge.stats.calls, net.bridge.stats.refused) == (3, 3)
    server.undeclare()
    token.undeclare()
    wait_until(lambda: net.bridge.routes() == {}, "the service gone with its server")


def test_a_name_that_is_not_fully_qualified_is_never_bridged_under_another_worlds_prefix(net: Net) -> None:
    # In world ada, "m/chatter" would be joined as /ada + m/chatter = /adam/chatter: world adam's.
    net.bridge.set_world(1, "ada")
    net.bridge.set_world(2, "adam")
    keep = [net.declare(EntityKind.PUBLISHER, "/chatter", 2, domain_id=2)]
    keep += [net.declare(kind, "m/chatter", 3 + i) for i, kind in enumerate(domain_routes.BRIDGED)]
    keep += [
        net.declare(EntityKind.PUBLISHER, topic, 10 + i) for i, topic in enumerate(("/a//b", "/x/", "~/x"))
    ]
    keep.append(
        net.declare(EntityKind.PUBLISHER, "/probe", 20)
    )  # after the others: once it shows, all were read
    wait_until(lambda: "ada" in net.bridge.routes() and "adam" in net.bridge.routes(), "both worlds bridged")
    assert net.bridge.routes() == {"ada": ["out /ada/probe"], "adam": ["out /adam/chatter"]}
    assert net.bridge.refused_names() == {"ada": 6}
    assert not [t for t in net.class_tokens() if "%ada/domain_bridge/%adam" in t]
    for token in keep:
        token.undeclare()


def test_a_token_in_one_world_costs_the_bridge_that_worlds_routes_only(net: Net) -> None:
    net.bridge.set_world(1, "ada")
    net.bridge.set_world(2, "bob")
    keep = [net.declare(EntityKind.PUBLISHER, f"/ada{i}", 10 + i) for i in range(20)]
    keep.append(net.declare(EntityKind.PUBLISHER, "/first", 2, domain_id=2))
    wait_until(
        lambda: len(net.bridge.routes().get("ada", [])) == 20 and "bob" in net.bridge.routes(),
        "ada's twenty topics and bob's first",
    )
    looked = net.bridge.routes_looked_at
    keep.append(net.declare(EntityKind.PUBLISHER, "/second", 3, domain_id=2))
    wait_until(lambda: len(net.bridge.routes()["bob"]) == 2, "bob's second topic")
    # bob's two routes and one mirror were looked at (at most twice, had the token come in two
    # passes), never ada's twenty: a student's node joining costs their own world's routes.
    assert 3 <= net.bridge.routes_looked_at - looked <= 6
    for token in keep:
        token.undeclare()
    wait_until(lambda: net.bridge.routes() == {}, "every route gone with its token")


def test_declarations_come_in_slices_with_the_interpreter_let_go_between(
    net: Net, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(domain_bridge, "SLICE", 4)
    keep = [net.declare(EntityKind.PUBLISHER, f"/t{i}", 10 + i) for i in range(10)]
    # A marker in a named world, declared after ada's by the same session: once it is bridged,
    # the bridge has heard all ten of ada's, which wait for their world to be named.
    net.bridge.set_world(2, "marker")
    keep.append(net.declare(EntityKind.PUBLISHER, "/marker", 3, domain_id=2))
    wait_until(lambda: "marker" in net.bridge.routes(), "the marker bridged")
    pauses = net.bridge.pauses
    net.bridge.set_world(1, "ada")  # one change: the ten declared in one pass
    wait_until(lambda: len(net.bridge.routes().get("ada", [])) == 10, "ada's ten topics")
    assert net.bridge.pauses - pauses == 2  # after the 4th and the 8th
    for token in keep:
        token.undeclare()
    wait_until(lambda: net.bridge.routes() == {}, "every route gone with its token")
