"""The whole graph: this process's nodes and topics with those other processes declare on Zenoh.

Every node and endpoint says where it runs: ``app`` (this process) or ``zenoh:<session>`` (another
process, which the session id names as ``ros2`` tools name a participant). Endpoints on one topic
name that disagree on its type are not merged: each type is a topic entry of its own, all of them
marked as conflicting, as two ROS 2 types on one name never meet on the wire.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from node_runtime.bus import INTERNAL_TOPICS, Bus, is_hidden
from node_runtime.transport.keys import EntityKind
from node_runtime.transport.remote_graph import RemoteGraph

LOCAL = "app"


@dataclass(frozen=True)
class EndpointView:
    node: str
    depth: int
    location: str


@dataclass
class TopicView:
    name: str
    type: str
    publishers: list[EndpointView] = field(default_factory=list)
    subscribers: list[EndpointView] = field(default_factory=list)
    type_conflict: bool = False
    local: bool = False  # this process has the topic (so it has a latest message and counts)

    @property
    def hidden(self) -> bool:
        return self.name in INTERNAL_TOPICS or is_hidden(self.name)

    @property
    def graph_id(self) -> str:
        """The name, or for a conflicting type the name with its type, so each entry is one box."""
        return f"{self.name} [{self.type}]" if self.type_conflict and not self.local else self.name


@dataclass(frozen=True)
class NodeView:
    name: str
    namespace: str
    state: str
    location: str

    @property
    def hidden(self) -> bool:
        return is_hidden(self.name)


def remote_graph(bus: Bus) -> RemoteGraph | None:
    """What other processes declare on the graph, when the bus is joined to Zenoh."""
    remote = bus.remote_topics
    return remote if isinstance(remote, RemoteGraph) else None


def topic_views(bus: Bus, remote: RemoteGraph | None) -> list[TopicView]:
    """Every topic of the graph, by name then type."""
    views: dict[tuple[str, str], TopicView] = {}
    for topic in bus.topics.values():
        view = views[(topic.name, topic.msg_type.TYPE)] = TopicView(
            topic.name, topic.msg_type.TYPE, local=True
        )
        view.publishers += [
            EndpointView(p.node.fully_qualified_name, p.depth, LOCAL) for p in topic.publishers
        ]
        view.subscribers += [
            EndpointView(s.node.fully_qualified_name, s.depth, LOCAL) for s in topic.subscriptions
        ]
    if remote is not None:
        for e in remote.endpoints([EntityKind.PUBLISHER, EntityKind.SUBSCRIPTION]):
            view = views.setdefault((e.name, e.type_name), TopicView(e.name, e.type_name))
            side = view.publishers if e.kind is EntityKind.PUBLISHER else view.subscribers
            side.append(EndpointView(e.node, e.depth, remote.location(e.zid)))
    names: dict[str, int] = {}
    for name, _ in views:
        names[name] = names.get(name, 0) + 1
    for (name, _), view in views.items():
        view.type_conflict = names[name] > 1
    return [views[key] for key in sorted(views)]


def node_views(bus: Bus, remote: RemoteGraph | None) -> list[NodeView]:
    """Every node of the graph: this process's, then other processes', by name."""
    nodes = [NodeView(n.fully_qualified_name, n.get_namespace(), n.state, LOCAL) for n in bus.nodes]
    if remote is not None:
        nodes += [NodeView(n.name, n.namespace, "active", n.location) for n in remote.nodes()]
    return sorted(nodes, key=lambda n: (n.name, n.location))


def remote_node_endpoints(remote: RemoteGraph, name: str) -> dict[str, list[dict[str, object]]]:
    """A node of another process, as ``ros2 node info`` lists it."""
    out: dict[str, list[dict[str, object]]] = {
        "publishers": [],
        "subscribers": [],
        "services": [],
        "clients": [],
    }
    keys = {
        EntityKind.PUBLISHER: "publishers", EntityKind.SUBSCRIPTION: "subscribers",
        EntityKind.SERVICE: "services", EntityKind.CLIENT: "clients",
    }  # fmt: skip
    for e in remote.endpoints():
        if e.node == name:
            out[keys[e.kind]].append({"topic": e.name, "type": e.type_name, "depth": e.depth})
    return out
