"""KeyboardManager (the handout's solution): /keydown → /abort_takeoff at 10 Hz, true from the first "a" on."""

from __future__ import annotations

from node_runtime.bus import Node
from node_runtime.msgs import Bool, Key


class KeyboardManager(Node):
    def __init__(self) -> None:
        super().__init__("KeyboardManagerNode")
        self.abort_pub = self.create_publisher(Bool, "/abort_takeoff", 1)
        self.key_sub = self.create_subscription(Key, "/keydown", self.get_key, 1)
        self.abort = Bool()
        self.key_code = -1
        self.timer = self.create_timer(1 / 10, self.process_key_code)

    def get_key(self, msg: Key) -> None:
        self.key_code = msg.code

    def process_key_code(self) -> None:
        if self.key_code == Key.KEY_A:
            self.get_logger().info("a key was pressed!")
            self.abort.data = True
        self.abort_pub.publish(self.abort)
        if self.key_code != -1:
            self.key_code = -1
