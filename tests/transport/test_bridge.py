"""The bus over Zenoh between two sessions: delivery, keep-last, the attachment rule, the graph, services."""

from __future__ import annotations

from types import SimpleNamespace
from typing import Any

import pytest

from node_runtime.bus import ManualClock, Node
from node_runtime.msgs import Int64, String, get_service_type
from node_runtime.msgs.wire import dds_type_name, serialize, type_hash
from node_runtime.transport import bridge as bridge_module
from node_runtime.transport.attachment import Attachment
from node_runtime.transport.keys import RELIABLE, TRANSIENT_LOCAL, EntityKind, EntityToken, data_key

from .conftest import Pair, joined

AddTwoInts = get_service_type("example_interfaces/srv/AddTwoInts")
Trigger = get_service_type("std_srvs/srv/Trigger")
INT64_KEY = data_key(0, "/x", dds_type_name("std_msgs/msg/Int64"), type_hash("std_msgs/msg/Int64"))


def _listener(pair: Pair, topic: str = "/x", depth: int = 10) -> list[int]:
    heard: list[int] = []
    Node("listener", context=pair.proc.bus).create_subscription(
        Int64, topic, lambda m: heard.append(m.data), depth
    )
    return heard


def _raw_publisher(pair: Pair, key: str) -> Any:
    """A bare Zenoh publisher in the app's session, once the other side's subscriber is known to it."""
    session: Any = pair.app.session
    raw = session.declare_publisher(key)
    pair.pump(lambda: raw.matching_status.matching, "the raw publisher to see the subscriber")
    return raw


def _talker(pair: Pair, topic: str = "/x") -> Any:
    return Node("talker", context=pair.app.bus).create_publisher(Int64, topic, 10)


def test_message_published_in_one_process_reaches_the_other(pair: Pair) -> None:
    heard = _listener(pair)
    pub = _talker(pair)
    pair.pump(lambda: pub.remote.matching, "the publisher to see the remote subscription")
    for i in range(5):
        pub.publish(Int64(data=i))
    pair.pump(lambda: heard == [0, 1, 2, 3, 4], "five messages in order")
    assert pair.proc.bridge.stats.received == 5 and pair.app.bridge.stats.sent == 5


def test_local_subscription_gets_each_local_message_once_while_the_topic_also_goes_out(pair: Pair) -> None:
    remote = _listener(pair)
    pub = _talker(pair)
    local: list[int] = []
    Node("local", context=pair.app.bus).create_subscription(Int64, "/x", lambda m: local.append(m.data), 10)
    pair.pump(lambda: pub.remote.matching, "matching")
    for i in range(3):
        pub.publish(Int64(data=i))
    pair.pump(lambda: remote == [0, 1, 2], "the remote copies")
    pair.pump(lambda: local == [0, 1, 2], "the local copies")
    assert pair.app.bridge.stats.received == 0  # nothing came back from Zenoh to its own process


def test_topic_nobody_outside_wants_is_never_serialized(pair: Pair) -> None:
    pub = _talker(pair)
    Node("local", context=pair.app.bus).create_subscription(Int64, "/x", lambda m: None, 10)
    pair.pump(lambda: True, "a pass")
    for i in range(10):
        pub.publish(Int64(data=i))
    assert not pub.remote.matching and pair.app.bridge.stats.sent == 0


def test_remote_samples_keep_last_by_subscription_depth(pair: Pair) -> None:
    heard = _listener(pair, depth=2)
    pub = _talker(pair)
    pair.pump(lambda: pub.remote.matching, "matching")
    inbox = pair.proc.bridge.inbox
    for i in range(10):
        pub.publish(Int64(data=i))
    # The node process is busy (its executor does not run) while all ten arrive.
    pair.pump(lambda: inbox.dropped_samples == 8, "all ten to arrive", spin=False)
    assert inbox.queued("/x") == 2
    pair.pump(lambda: heard == [8, 9], "the two newest")


def test_sample_without_rmw_zenoh_attachment_is_dropped_and_counted(pair: Pair) -> None:
    heard = _listener(pair)
    raw = _raw_publisher(pair, INT64_KEY)
    raw.put(serialize(Int64(data=7)))
    pair.pump(lambda: pair.proc.bridge.stats.no_attachment == 1, "the bare sample to be counted")
    raw.put(serialize(Int64(data=8)), attachment=Attachment(1, 0, bytes(16)).pack())
    pair.pump(lambda: heard == [8], "the sample with its attachment")


def test_a_bridge_with_a_sample_budget_drops_a_flood_as_it_arrives() -> None:
    # A class world's bridge takes at most samples_hz a second from other processes (bursts of one
    # second's worth), on its own clock: the rest are counted and never decoded or delivered.
    clock = ManualClock()
    with joined(samples_hz=10.0, clock=clock) as pair:
        heard = _listener(pair)
        raw = _raw_publisher(pair, INT64_KEY)
        for i in range(50):
            raw.put(serialize(Int64(data=i)), attachment=Attachment(i + 1, 0, bytes(16)).pack())
        pair.pump(lambda: pair.proc.bridge.stats.over_rate == 40, "40 of 50 samples dropped in one instant")
        pair.pump(lambda: len(heard) == 10, "the first ten delivered")
        assert heard == list(range(10))
        clock.set(1.0)  # a second later: ten more
        for i in range(50, 65):
            raw.put(serialize(Int64(data=i)), attachment=Attachment(i + 1, 0, bytes(16)).pack())
        pair.pump(lambda: pair.proc.bridge.stats.over_rate == 45, "5 of the next 15 dropped")
        pair.pump(lambda: len(heard) == 20, "ten more delivered")
        assert heard[10:] == list(range(50, 60))
        assert pair.app.bridge.stats.over_rate == 0  # a bridge without a budget takes all


def test_undecodable_sample_is_counted_not_delivered(pair: Pair) -> None:
    heard = _listener(pair)
    raw = _raw_publisher(pair, INT64_KEY)
    raw.put(b"\x00\x01\x00\x00\x01", attachment=Attachment(1, 0, bytes(16)).pack())
    raw.put(serialize(Int64(data=3)), attachment=Attachment(2, 0, bytes(16)).pack())
    pair.pump(lambda: heard == [3], "the good sample")
    assert pair.proc.bridge.stats.undecodable == 1


def test_attachments_carry_sequence_from_one_and_the_publisher_token_gid(pair: Pair) -> None:
    got: list[Attachment | None] = []
    raw: Any = pair.proc.session
    sub = raw.declare_subscriber(INT64_KEY, lambda s: got.append(Attachment.unpack(s.attachment.to_bytes())))
    try:
        pub = _talker(pair)
        pair.pump(lambda: pub.remote.matching, "matching")
        for i in range(4):
            pub.publish(Int64(data=i))
        pair.pump(lambda: len(got) == 4, "four samples")
    finally:
        sub.undeclare()
    token = next(e.token for e in pair.app.bridge._entities.values() if e.token.kind is EntityKind.PUBLISHER
                 and e.token.topic == "/x")  # fmt: skip
    assert [a.sequence_number for a in got if a] == [1, 2, 3, 4]
    assert all(a is not None and a.gid == token.gid for a in got)


def test_graph_of_each_side_lists_the_other_sides_nodes_and_forgets_them(pair: Pair) -> None:
    node = Node("talker", context=pair.app.bus)
    node.create_publisher(Int64, "/x", 10)
    seen = pair.proc.bridge.remote

    def publisher_seen() -> bool:
        return any(
            e.name == "/x" and e.type_name == "std_msgs/msg/Int64" and e.node == "/talker"
            for e in seen.endpoints([EntityKind.PUBLISHER])
        )

    pair.pump(publisher_seen, "the publisher in the other graph")
    assert "/talker" in [n.name for n in seen.nodes()]
    assert all(n.zid == pair.app.bridge.zid for n in seen.nodes())
    node.destroy_node()
    pair.pump(lambda: "/talker" not in [n.name for n in seen.nodes()], "the node to leave the other graph")


def test_messages_of_another_type_on_the_same_name_never_meet(pair: Pair) -> None:
    strings: list[str] = []
    Node("listener", context=pair.proc.bus).create_subscription(
        String, "/x", lambda m: strings.append(m.data), 10
    )
    pub = _talker(pair)
    pair.pump(lambda: any(e.type_name == "std_msgs/msg/String" for e in pair.app.bridge.remote.endpoints()),
              "the other type in the graph")  # fmt: skip
    pub.publish(Int64(data=1))
    pair.pump(lambda: True, "a pass")
    assert not pub.remote.matching and strings == []


def test_service_call_from_the_node_process_to_the_app(pair: Pair) -> None:
    def add(request: Any, response: Any) -> Any:
        response.sum = request.a + request.b
        return response

    Node("adder", context=pair.app.bus).create_service(AddTwoInts, "/add", add)
    client = Node("caller", context=pair.proc.bus).create_client(AddTwoInts, "/add")
    pair.pump(client.service_is_ready, "the remote server to be seen")
    future = client.call_async(AddTwoInts.Request(a=20, b=22))
    pair.pump(future.done, "the reply")
    assert future.result() == AddTwoInts.Response(sum=42)


def test_service_call_from_the_app_to_the_node_process(pair: Pair) -> None:
    def trigger(request: Any, response: Any) -> Any:
        response.success, response.message = True, "done there"
        return response

    Node("server", context=pair.proc.bus).create_service(Trigger, "/go", trigger)
    client = Node("caller", context=pair.app.bus).create_client(Trigger, "/go")
    pair.pump(client.service_is_ready, "the remote server to be seen")
    future = client.call_async(Trigger.Request())
    pair.pump(future.done, "the reply")
    assert future.result() == Trigger.Response(success=True, message="done there")
    assert not Node("other", context=pair.app.bus).create_client(AddTwoInts, "/go2").service_is_ready()


def test_a_late_transient_local_subscription_gets_its_own_process_history_once(pair: Pair) -> None:
    latched = SimpleNamespace(depth=3, durability=TRANSIENT_LOCAL, reliability=RELIABLE)
    node = Node("latched", context=pair.app.bus)
    pub = node.create_publisher(Int64, "/map", latched)
    for i in range(5):
        pub.publish(Int64(data=i))
    late: list[int] = []
    volatile: list[int] = []
    node.create_subscription(Int64, "/map", lambda m: late.append(m.data), latched)
    node.create_subscription(Int64, "/map", lambda m: volatile.append(m.data), 10)
    # The late subscription's history query is answered by the publisher's cache in this very
    # session too: those three come back over Zenoh, and are dropped as the echoes they are.
    pair.pump(lambda: pair.app.bridge.stats.echoes == 3, "the kept messages to come back over Zenoh")
    pub.publish(Int64(data=5))
    pair.pump(lambda: 5 in volatile, "the message published after the subscriptions")
    assert late == [2, 3, 4, 5]
    assert volatile == [5]
    assert pair.app.bridge.stats.received == 0


def test_a_flood_of_graph_tokens_is_taken_a_bounded_slice_a_pass(
    pair: Pair, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(bridge_module, "MAX_EVENTS_PER_POLL", 4)
    side = pair.proc
    side.executor.spin_some()  # whatever the join brought in, taken first
    wakes: list[None] = []
    side.bus.threadsafe_waker = lambda: wakes.append(None)
    # Ten nodes of another process joining at once, as a class's burst brings them.
    for i in range(10):
        token = EntityToken(0, "0a" * 8, i + 1, i + 1, EntityKind.NODE, "/", f"n{i}")
        side.bridge.inbox.post(("token", token.key, True))
    wakes.clear()
    seen = side.bridge.remote
    before = {n.name for n in seen.nodes()}
    side.bridge.poll()
    assert len({n.name for n in seen.nodes()} - before) == 4 and len(wakes) == 1  # the next pass asked for
    side.bridge.poll()
    assert len({n.name for n in seen.nodes()} - before) == 8 and len(wakes) == 2
    side.bridge.poll()  # the last two: nothing left, no pass asked for
    assert len({n.name for n in seen.nodes()} - before) == 10 and len(wakes) == 2
