"""talker: "Hello World: N" on /chatter once a second, logging each as demo_nodes_py's does."""

from __future__ import annotations

from node_runtime.bus import Node
from node_runtime.msgs import String

PERIOD_S = 1.0


class Talker(Node):
    FIRST = 0  # the N of the first message
    LINE = 'Publishing: "{}"'  # the log line of each message
    DEPTH = 10  # the publisher's history

    def __init__(self) -> None:
        super().__init__("talker")
        self.count = self.FIRST
        self.pub = self.create_publisher(String, "chatter", self.DEPTH, hand_over=True)
        self.create_timer(PERIOD_S, self.publish)

    def publish(self) -> None:
        msg = String(data=f"Hello World: {self.count}")
        self.count += 1
        self.get_logger().info(self.LINE.format(msg.data))
        self.pub.publish(msg)
