"""listener: logs each String heard on /chatter as ROS 2's demo listeners do."""

from __future__ import annotations

from node_runtime.bus import Node
from node_runtime.msgs import String


class Listener(Node):
    def __init__(self) -> None:
        super().__init__("listener")
        self.create_subscription(String, "chatter", self.on_chatter, 10, read_only=True)

    def on_chatter(self, msg: String) -> None:
        self.get_logger().info(f"I heard: [{msg.data}]")
