"""A lab whose ./workspace holds the handout's files (examples/workspace) and the tests' own nodes,
run as ``python -m server`` in a subprocess, with keys sent as the page sends them."""

from __future__ import annotations

import json
import shutil
import textwrap
from collections.abc import Iterator
from pathlib import Path

import pytest
from support.app import REPO, App
from websockets.sync.client import ClientConnection, connect

EXAMPLES = REPO / "examples" / "workspace"

# The handout's "Method 1": a rate and a loop in main() instead of a timer.
RATE_NODE = """
import rclpy
from rclpy.node import Node
from std_msgs.msg import Int64


def main():
    rclpy.init()
    node = Node('RateNode')
    pub = node.create_publisher(Int64, '/rate_demo', 10)
    rate = node.create_rate(5)
    count = 0
    try:
        while rclpy.ok():
            count += 1
            pub.publish(Int64(data=count))
            rate.sleep()
    except KeyboardInterrupt:
        pass
    finally:
        rclpy.try_shutdown()


if __name__ == '__main__':
    main()
"""

CRASHES = """
import rclpy
from rclpy.node import Node


class Crasher(Node):
    def __init__(self):
        super().__init__('Crasher')
        self.create_timer(0.5, self.tick)

    def tick(self):
        raise RuntimeError('sensor unplugged')


if __name__ == '__main__':
    rclpy.init()
    rclpy.spin(Crasher())
"""

SPINS_FOREVER = """
import rclpy
from rclpy.node import Node


class Busy(Node):
    def __init__(self):
        super().__init__('Busy')
        self.create_timer(0.2, self.tick)

    def tick(self):
        self.get_logger().info('into the endless callback')
        while True:
            pass


if __name__ == '__main__':
    rclpy.init()
    rclpy.spin(Busy())
"""


def make_workspace(root: Path, extra: dict[str, str] | None = None) -> Path:
    """``root/workspace``: the handout's packages, plus ``extra`` files (path in the workspace → text)."""
    workspace = root / "workspace"
    shutil.copytree(EXAMPLES, workspace)
    for rel, text in (extra or {}).items():
        path = workspace / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(textwrap.dedent(text).lstrip())
    return workspace


class Keys:
    """The page's key channel."""

    def __init__(self, app: App) -> None:
        self.ws: ClientConnection = connect(f"ws://127.0.0.1:{app.port}/ws/keys")

    def press(self, key: str) -> None:
        self.ws.send(json.dumps({"type": "keydown", "key": key}))
        self.ws.send(json.dumps({"type": "keyup", "key": key}))

    def close(self) -> None:
        self.ws.close()


@pytest.fixture
def keys_for() -> Iterator[type[Keys]]:
    opened: list[Keys] = []

    class Opened(Keys):
        def __init__(self, app: App) -> None:
            super().__init__(app)
            opened.append(self)

    yield Opened
    for k in opened:
        k.close()


def node_entry(app: App, name: str) -> dict[str, object] | None:
    return next((n for n in app.get("/api/nodes") if n["name"] == name), None)


def pid_alive(pid: int) -> bool:
    try:
        Path(f"/proc/{pid}/status").read_text()
    except FileNotFoundError:
        return False
    return "State:\tZ" not in Path(f"/proc/{pid}/status").read_text()
