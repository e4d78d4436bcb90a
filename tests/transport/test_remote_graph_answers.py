"""The remote graph's answers (node_runtime/transport/remote_graph.py) are built once per change:
asked again with nothing changed they are not built anew, and every change (a token in, a token
gone, a session gone, a session named) is in the next answer; a caller that changes a list it
was given changes nothing the next caller gets."""

from __future__ import annotations

import pytest

from node_runtime.transport.keys import EntityKind, EntityToken, keep_last
from node_runtime.transport.remote_graph import RemoteGraph

ZID = "a" * 32
OTHER = "b" * 32


def node(zid: str, name: str, node_id: int) -> EntityToken:
    return EntityToken(0, zid, node_id, 0, EntityKind.NODE, "/", name)


def publisher(zid: str, name: str, node_id: int, topic: str, dds_type: str) -> EntityToken:
    return EntityToken(
        0,
        zid,
        node_id,
        1,
        EntityKind.PUBLISHER,
        "/",
        name,
        "/",
        topic,
        dds_type,
        "RIHS01_" + "0" * 64,
        keep_last(10),
    )


@pytest.fixture
def graph() -> RemoteGraph:
    graph = RemoteGraph("f" * 32, 0)
    for token in (
        node(ZID, "talker", 1),
        publisher(ZID, "talker", 1, "/chatter", "std_msgs::msg::dds_::String_"),
    ):
        assert graph.apply(token.key, True)
    return graph


def test_asked_again_unchanged_the_answers_are_not_built_anew(
    graph: RemoteGraph, monkeypatch: pytest.MonkeyPatch
) -> None:
    first = (graph.endpoints(), graph.nodes(), dict(graph.topic_types()))
    built: list[object] = []
    real = graph._endpoints
    monkeypatch.setattr(graph, "_endpoints", lambda wanted: built.append(wanted) or real(wanted))
    for _ in range(3):
        assert (graph.endpoints(), graph.nodes(), dict(graph.topic_types())) == first
    assert built == []
    assert graph.apply(publisher(OTHER, "echo", 2, "/chatter", "std_msgs::msg::dds_::String_").key, True)
    assert len(graph.endpoints()) == 2 and built  # a change: built again


def test_every_change_is_in_the_next_answer(graph: RemoteGraph) -> None:
    assert graph.topic_types() == {"/chatter": {"std_msgs/msg/String"}}
    assert [n.location for n in graph.nodes()] == [f"zenoh:{ZID[:8]}"]
    graph.name_session(ZID, "process 42")
    assert [n.location for n in graph.nodes()] == ["process 42"]
    other = publisher(OTHER, "odd", 3, "/chatter", "std_msgs::msg::dds_::Int64_")
    graph.apply(other.key, True)
    assert graph.topic_types() == {"/chatter": {"std_msgs/msg/String", "std_msgs/msg/Int64"}}
    graph.apply(other.key, False)
    assert graph.topic_types() == {"/chatter": {"std_msgs/msg/String"}}
    assert graph.drop_session(ZID)
    assert (graph.endpoints(), graph.nodes(), dict(graph.topic_types())) == ([], [], {})


def test_a_list_changed_by_its_caller_is_not_the_next_callers(graph: RemoteGraph) -> None:
    endpoints, nodes = graph.endpoints(), graph.nodes()
    endpoints.clear()
    nodes.clear()
    assert len(graph.endpoints()) == 1 and len(graph.nodes()) == 1
    assert [e.kind for e in graph.endpoints([EntityKind.SUBSCRIPTION])] == []
    assert [e.kind for e in graph.endpoints([EntityKind.PUBLISHER])] == [EntityKind.PUBLISHER]
