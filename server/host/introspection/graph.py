"""rqt_graph's view of the graph: nodes, topics and publish/subscribe edges, as plain data, with the
nodes of other processes (server.host.introspection.merged) beside this process's own."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from node_runtime.bus import Bus
from node_runtime.transport.remote_graph import RemoteGraph
from server.host.introspection.merged import node_views, topic_views

EdgeKind = Literal["publish", "subscribe"]


@dataclass(frozen=True)
class GraphNode:
    name: str
    state: str
    hidden: bool
    location: str = "app"


@dataclass(frozen=True)
class GraphTopic:
    name: str
    type: str
    hidden: bool
    type_conflict: bool = False


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


def graph_snapshot(
    bus: Bus, include_hidden: bool = False, remote: RemoteGraph | None = None
) -> GraphSnapshot:
    """The computation graph, sorted by name; hidden nodes, internal topics and their edges are left
    out unless ``include_hidden``. A node with two endpoints on one topic gives one edge. A topic
    whose endpoints disagree on its type is one box per type (the other types' boxes are named
    ``/topic [pkg/msg/Type]``)."""
    nodes = [
        GraphNode(n.name, n.state, n.hidden, n.location)
        for n in node_views(bus, remote)
        if include_hidden or not n.hidden
    ]
    shown = {n.name for n in nodes}
    topics: list[GraphTopic] = []
    edges: dict[GraphEdge, None] = {}  # an ordered set
    for topic in topic_views(bus, remote):
        if topic.hidden and not include_hidden:
            continue
        box = topic.graph_id
        topics.append(GraphTopic(box, topic.type, topic.hidden, topic.type_conflict))
        for pub in topic.publishers:
            if pub.node in shown:
                edges[GraphEdge(pub.node, box, "publish")] = None
        for sub in topic.subscribers:
            if sub.node in shown:
                edges[GraphEdge(box, sub.node, "subscribe")] = None
    version = bus.graph_version + (remote.version if remote is not None else 0)
    return GraphSnapshot(version, nodes, topics, list(edges))
