"""rosapi: the graph as services (``/rosapi/topics``, ``/rosapi/nodes`` ...), as rosbridge's rosapi
node serves them and roslibjs' ``getTopics`` or roslibpy's ``get_nodes`` call them.

Hidden topics and nodes (``_``-prefixed) are left out, as ``ros2 topic list`` leaves them out.
"""

from __future__ import annotations

from typing import Any

from server.bus import Node, RosTime, is_hidden
from server.msgs import get_service_type

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

    def _visible_nodes(self) -> list[Node]:
        return [n for n in self.bus.nodes if not n.get_name().startswith("_")]

    def _nodes(self, _request: Any, response: Any) -> Any:
        response.nodes = sorted(n.fully_qualified_name for n in self._visible_nodes())
        return response

    def _node_details(self, request: Any, response: Any) -> Any:
        wanted = self._absolute(request.node)
        node = next((n for n in self.bus.nodes if n.fully_qualified_name == wanted), None)
        if node is not None:
            response.subscribing = sorted({s.topic_name for s in node.subscriptions})
            response.publishing = sorted({p.topic_name for p in node.publishers})
            response.services = sorted({s.srv_name for s in node.services})
        return response

    def _publishers(self, request: Any, response: Any) -> Any:
        topic = self.bus.topics.get(self._absolute(request.topic))
        response.publishers = (
            sorted({p.node.fully_qualified_name for p in topic.publishers}) if topic is not None else []
        )
        return response

    def _subscribers(self, request: Any, response: Any) -> Any:
        topic = self.bus.topics.get(self._absolute(request.topic))
        response.subscribers = (
            sorted({s.node.fully_qualified_name for s in topic.subscriptions}) if topic is not None else []
        )
        return response

    def _services(self, _request: Any, response: Any) -> Any:
        response.services = sorted(name for name in self.bus.services if not is_hidden(name))
        return response

    def _service_type(self, request: Any, response: Any) -> Any:
        channel = self.bus.services.get(self._absolute(request.service))
        response.type = channel.srv_type.TYPE if channel is not None else ""
        return response

    def _get_time(self, _request: Any, response: Any) -> Any:
        response.time = RosTime.from_seconds(self.bus.clock.now()).to_msg()
        return response
