"""``graph_snapshot``: rqt_graph's view of a bus: hidden names, edges without duplicates, no stale parts."""

from __future__ import annotations

from node_runtime.bus import Bus, Executor, Node
from node_runtime.msgs import Int64
from server.host.introspection import GraphEdge, graph_snapshot, node_info


def _chatter(bus: Bus) -> tuple[Node, Node, Node]:
    talker = Node("talker", context=bus)
    talker.create_publisher(Int64, "/chatter", 10)
    talker.create_publisher(Int64, "/chatter", 10)  # a second publisher on the same topic
    listener = Node("listener", context=bus)
    listener.create_subscription(Int64, "/chatter", lambda _m: None, 10)
    spy = Node("_spy", context=bus)
    spy.create_subscription(Int64, "/chatter", lambda _m: None, 10)
    return talker, listener, spy


def test_graph_snapshot_default_leaves_out_hidden_nodes_internal_topics_and_their_edges(bus: Bus) -> None:
    _chatter(bus)
    snap = graph_snapshot(bus)
    assert [n.name for n in snap.nodes] == ["/listener", "/talker"]
    assert [t.name for t in snap.topics] == ["/chatter"]
    assert snap.edges == [
        GraphEdge("/talker", "/chatter", "publish"),
        GraphEdge("/chatter", "/listener", "subscribe"),
    ]


def test_graph_snapshot_include_hidden_adds_spy_rosout_and_parameter_events_flagged_hidden(bus: Bus) -> None:
    _chatter(bus)
    snap = graph_snapshot(bus, include_hidden=True)
    assert {n.name: n.hidden for n in snap.nodes} == {"/_spy": True, "/listener": False, "/talker": False}
    topics = {t.name: t.hidden for t in snap.topics}
    assert topics == {"/chatter": False, "/rosout": True, "/parameter_events": True}
    assert GraphEdge("/chatter", "/_spy", "subscribe") in snap.edges
    assert GraphEdge("/talker", "/rosout", "publish") in snap.edges
    assert GraphEdge("/talker", "/parameter_events", "publish") in snap.edges


def test_graph_snapshot_two_publishers_on_one_topic_give_one_edge(bus: Bus) -> None:
    _chatter(bus)
    edges = graph_snapshot(bus, include_hidden=True).edges
    assert len(edges) == len(set(edges))
    assert edges.count(GraphEdge("/talker", "/chatter", "publish")) == 1


def test_graph_snapshot_after_destroy_node_has_neither_it_nor_its_unused_topics(bus: Bus) -> None:
    talker, _listener, _spy = _chatter(bus)
    talker.create_publisher(Int64, "/only_talker", 10)
    before = graph_snapshot(bus)
    talker.destroy_node()
    after = graph_snapshot(bus)
    assert after.version > before.version
    assert "/talker" not in [n.name for n in after.nodes]
    assert [t.name for t in after.topics] == ["/chatter"]  # still subscribed
    assert all("/talker" not in (e.source, e.target) for e in after.edges)


def test_graph_snapshot_node_crashing_in_a_timer_shows_crashed_and_bumps_version(
    bus: Bus, executor: Executor
) -> None:
    node = Node("fragile", context=bus)

    def fail() -> None:
        raise RuntimeError("sensor unplugged")

    node.create_timer(0.5, fail)
    before = graph_snapshot(bus)
    executor.spin_until(1.0)
    after = graph_snapshot(bus)
    assert after.version > before.version
    assert [(n.name, n.state) for n in after.nodes] == [("/fragile", "crashed")]
    assert node_info(node)["crash_reason"] == "RuntimeError: sensor unplugged"
