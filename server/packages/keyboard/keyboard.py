"""keyboard_node: publishes a Key on /keydown and /keyup for each key event of the browser keyboard.

Where the original polls an SDL window at 50 Hz, this publishes as soon as the event arrives.
Auto-repeat is off unless ``allow_repeat`` is set, as in the original.
"""

from __future__ import annotations

from node_runtime.bus import Node
from node_runtime.msgs import Key
from server.peripherals.devices.keyboard import KeyboardDevice, KeyEvent

DEVICE = "keyboard"


class KeyboardNode(Node):
    def __init__(self) -> None:
        super().__init__("keyboard_node")
        self.declare_parameter("allow_repeat", False)  # read at each key: ``ros2 param set`` takes effect
        self.pub_down = self.create_publisher(Key, "keydown", 10)
        self.pub_up = self.create_publisher(Key, "keyup", 10)
        self.device: KeyboardDevice | None = self.bus.devices.get(DEVICE)
        if self.device is None:
            self.get_logger().warning("no keyboard attached: no key will be published")
        else:
            self.device.add_listener(self.on_key)

    @property
    def allow_repeat(self) -> bool:
        """Whether a held key's repeats are published too (the ``allow_repeat`` parameter)."""
        return bool(self.get_parameter("allow_repeat").value)

    def on_key(self, event: KeyEvent) -> None:
        if self.state != "active":
            return
        if event.repeat and not self.allow_repeat:
            return
        msg = Key(code=event.code, modifiers=event.modifiers)
        msg.header.stamp = self.get_clock().now().to_msg()
        (self.pub_down if event.kind == "keydown" else self.pub_up).publish(msg)

    def destroy_node(self) -> bool:
        if self.device is not None:
            self.device.remove_listener(self.on_key)
        return super().destroy_node()
