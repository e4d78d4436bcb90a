"""rosapi: the graph as services (``/rosapi/topics``, ``/rosapi/nodes`` ...), as rosbridge's rosapi
node serves them and roslibjs' ``getTopics`` or roslibpy's ``get_nodes`` call them.

The graph is the whole graph: this process's nodes with those other processes declare on Zenoh
(a student's node process, a ROS 2 install with rmw_zenoh), as ``ros2 node list`` shows them all.
Hidden topics and nodes (``_``-prefixed) are left out, as ``ros2 topic list`` leaves them out.
"""

from __future__ import annotations

from typing import Any

from node_runtime.bus import Node, RosTime, is_hidden
from node_runtime.msgs import get_service_type
from node_runtime.transport.keys import EntityKind
from server.host.introspection.merged import node_views, remote_graph, remote_node_endpoints, topic_views

NAMESPACE = "/rosapi"


def _visible_topics(node: Node) -> list[tuple[str, str]]:
    """This process's topics and those other processes declare (``Bus.known_topics``)."""
    return sorted((name, t.TYPE) for name, t in node.bus.known_topics().items() if not is_hidden(name))


class RosapiNode(Node):
    """Hidden node ``_rosapi`` serving rosapi_msgs services under /rosapi."""

    def __init__(self) -> None:
        super().__init__("_rosapi")
        handlers = {
            "topics": ("Topics", self._topics),
            "topics_for_type": ("TopicsForType", self._topics_for_type),
            "topic_type": ("TopicType", self._topic_type),
            "nodes": ("Nodes", self._nodes),
            "node_details": ("NodeDetails", self._node_details),
            "publishers": ("Publishers", self._publishers),
            "subscribers": ("Subscribers", self._subscribers),
            "services": ("Services", self._services),
            "service_type": ("ServiceType", self._service_type),
            "get_time": ("GetTime", self._get_time),
        }
        for name, (srv, handler) in handlers.items():
            self.create_service(get_service_type(f"rosapi_msgs/srv/{srv}"), f"{NAMESPACE}/{name}", handler)

    def _absolute(self, name: str) -> str:
        return name if name.startswith("/") else "/" + name

    def _topics(self, _request: Any, response: Any) -> Any:
        pairs = _visible_topics(self)
        response.topics = [name for name, _ in pairs]
        response.types = [type_name for _, type_name in pairs]
        return response

    def _topics_for_type(self, request: Any, response: Any) -> Any:
        wanted = request.type.replace("/msg/", "/")
        response.topics = [n for n, t in _visible_topics(self) if t.replace("/msg/", "/") == wanted]
        return response

    def _topic_type(self, request: Any, response: Any) -> Any:
        msg_type = self.bus.topic_type(self._absolute(request.topic))
        response.type = msg_type.TYPE if msg_type is not None else ""
        return response

    def _nodes(self, _request: Any, response: Any) -> Any:
        views = node_views(self.bus, remote_graph(self.bus))
        response.nodes = sorted({n.name for n in views if not n.hidden})
        return response

    def _node_details(self, request: Any, response: Any) -> Any:
        wanted = self._absolute(request.node)
        node = next((n for n in self.bus.nodes if n.fully_qualified_name == wanted), None)
        if node is not None:
            response.subscribing = sorted({s.topic_name for s in node.subscriptions})
            response.publishing = sorted({p.topic_name for p in node.publishers})
            response.services = sorted({s.srv_name for s in node.services})
        elif (remote := remote_graph(self.bus)) is not None:
            found = remote_node_endpoints(remote, wanted)
            response.subscribing = sorted({str(e["topic"]) for e in found["subscribers"]})
            response.publishing = sorted({str(e["topic"]) for e in found["publishers"]})
            response.services = sorted({str(e["topic"]) for e in found["services"]})
        return response

    def _endpoint_nodes(self, topic: str, publishers: bool) -> list[str]:
        """Nodes of any process with a publisher (or a subscription) on ``topic``, of any type."""
        names: set[str] = set()
        for view in topic_views(self.bus, remote_graph(self.bus)):
            if view.name == topic:
                names.update(e.node for e in (view.publishers if publishers else view.subscribers))
        return sorted(names)

    def _publishers(self, request: Any, response: Any) -> Any:
        response.publishers = self._endpoint_nodes(self._absolute(request.topic), publishers=True)
        return response

    def _subscribers(self, request: Any, response: Any) -> Any:
        response.subscribers = self._endpoint_nodes(self._absolute(request.topic), publishers=False)
        return response

    def _remote_services(self) -> dict[str, str]:
        """Services other processes serve, with their types (the first type a name is served with)."""
        remote = remote_graph(self.bus)
        if remote is None:
            return {}
        out: dict[str, str] = {}
        for e in remote.endpoints([EntityKind.SERVICE]):
            out.setdefault(e.name, e.type_name)
        return out

    def _services(self, _request: Any, response: Any) -> Any:
        names = set(self.bus.services) | set(self._remote_services())
        response.services = sorted(name for name in names if not is_hidden(name))
        return response

    def _service_type(self, request: Any, response: Any) -> Any:
        name = self._absolute(request.service)
        channel = self.bus.services.get(name)
        response.type = (
            channel.srv_type.TYPE if channel is not None else self._remote_services().get(name, "")
        )
        return response

    def _get_time(self, _request: Any, response: Any) -> Any:
        response.time = RosTime.from_seconds(self.bus.clock.now()).to_msg()
        return response
