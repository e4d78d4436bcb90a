"""rqt_graph's view of a bus: nodes, topics and publish/subscribe edges, as plain data."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from server.bus import Bus, is_hidden

EdgeKind = Literal["publish", "subscribe"]


@dataclass(frozen=True)
class GraphNode:
    name: str
    state: str
    hidden: bool


@dataclass(frozen=True)
class GraphTopic:
    name: str
    type: str
    hidden: bool


@dataclass(frozen=True)
class GraphEdge:
    """``publish``: node → topic; ``subscribe``: topic → node (the way the data flows)."""

    source: str
    target: str
    kind: EdgeKind


@dataclass(frozen=True)
class GraphSnapshot:
    version: int
    nodes: list[GraphNode]
    topics: list[GraphTopic]
    edges: list[GraphEdge]


def graph_snapshot(bus: Bus, include_hidden: bool = False) -> GraphSnapshot:
    """The computation graph, sorted by name; hidden nodes, internal topics and their edges
    are left out unless ``include_hidden``. A node with two endpoints on one topic gives one edge."""
    nodes = [GraphNode(n.fully_qualified_name, n.state, is_hidden(n.fully_qualified_name)) for n in bus.nodes]
    nodes = sorted((n for n in nodes if include_hidden or not n.hidden), key=lambda n: n.name)
    shown = {n.name for n in nodes}
    topics: list[GraphTopic] = []
    edges: dict[GraphEdge, None] = {}  # an ordered set
    for topic in sorted(bus.topics.values(), key=lambda t: t.name):
        if topic.hidden and not include_hidden:
            continue
        topics.append(GraphTopic(topic.name, topic.msg_type.TYPE, topic.hidden))
        for pub in topic.publishers:
            if pub.node.fully_qualified_name in shown:
                edges[GraphEdge(pub.node.fully_qualified_name, topic.name, "publish")] = None
        for sub in topic.subscriptions:
            if sub.node.fully_qualified_name in shown:
                edges[GraphEdge(topic.name, sub.node.fully_qualified_name, "subscribe")] = None
    return GraphSnapshot(bus.graph_version, nodes, topics, list(edges))
