"""The hidden node ``_rest_api``: what the API publishes goes out through it (like rqt's publisher),
and the lab's own controls are served on it as ROS services (``/rocket/reset``)."""

from __future__ import annotations

from node_runtime.bus import Node, Publisher
from node_runtime.limits import LimitExceededError
from node_runtime.msgs import Message


class ApiNode(Node):
    """Hidden node ``_rest_api`` that owns the publishers REST calls use, one per topic."""

    def __init__(self, max_topics: int) -> None:
        super().__init__("_rest_api")
        self.max_topics = max_topics
        self.pubs: dict[str, Publisher] = {}

    def publisher_for(self, topic: str, msg_type: type[Message]) -> Publisher:
        pub = self.pubs.get(topic)
        if pub is not None and pub.msg_type is msg_type:
            return pub
        if pub is None and len(self.pubs) >= self.max_topics:
            raise LimitExceededError("topics published by the API", self.max_topics)
        pub = self.create_publisher(msg_type, topic, 10)
        self.pubs[topic] = pub
        return pub
