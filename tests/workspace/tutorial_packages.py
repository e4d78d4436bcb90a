"""Our own versions of ROS 2's example packages, laid out as ``git clone`` of ros2/examples leaves
them below ``src/``: ament_python packages named by their package.xml, with console_scripts."""

from __future__ import annotations

import textwrap
from pathlib import Path


def manifest(name: str, build_type: str = "ament_python") -> str:
    return textwrap.dedent(f"""\
        <?xml version="1.0"?>
        <package format="3">
          <name>{name}</name>
          <version>0.0.0</version>
          <description>test package</description>
          <maintainer email="student@example.com">student</maintainer>
          <license>Apache-2.0</license>
          <depend>rclpy</depend>
          <export>
            <build_type>{build_type}</build_type>
          </export>
        </package>
        """)


def setup_py(name: str, scripts: list[str]) -> str:
    lines = "".join(f"            '{s}',\n" for s in scripts)
    return (
        "from setuptools import find_packages, setup\n\n"
        f"package_name = '{name}'\n\n"
        "setup(\n    name=package_name,\n    version='0.0.0',\n    packages=find_packages(exclude=['test']),\n"
        "    entry_points={\n        'console_scripts': [\n" + lines + "        ],\n    },\n)\n"
    )


def write(root: Path, files: dict[str, str]) -> None:
    for rel, text in files.items():
        path = root / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(textwrap.dedent(text))


def python_package(folder: Path, name: str, scripts: list[str], modules: dict[str, str]) -> None:
    files = {
        "package.xml": manifest(name),
        "setup.py": setup_py(name, scripts),
        f"resource/{name}": "",
        f"{name}/__init__.py": "",
    }
    files |= {f"{name}/{module}.py": text for module, text in modules.items()}
    write(folder, files)


PUBLISHER = """
import rclpy
from rclpy.node import Node
from std_msgs.msg import String


class MinimalPublisher(Node):

    def __init__(self):
        super().__init__('minimal_publisher')
        self.publisher_ = self.create_publisher(String, 'topic', 10)
        self.timer = self.create_timer(0.2, self.timer_callback)
        self.i = 0

    def timer_callback(self):
        msg = String()
        msg.data = 'Hello World: %d' % self.i
        self.publisher_.publish(msg)
        self.get_logger().info('Publishing: "%s"' % msg.data)
        self.i += 1


def main(args=None):
    rclpy.init(args=args)
    minimal_publisher = MinimalPublisher()
    try:
        rclpy.spin(minimal_publisher)
    except KeyboardInterrupt:
        pass
    finally:
        minimal_publisher.destroy_node()
        rclpy.try_shutdown()
"""

SUBSCRIBER = """
import sys

import rclpy
from rclpy.node import Node
from std_msgs.msg import String

WANTED = 3


class MinimalSubscriber(Node):

    def __init__(self):
        super().__init__('minimal_subscriber')
        self.heard = 0
        self.subscription = self.create_subscription(String, 'topic', self.listener_callback, 10)

    def listener_callback(self, msg):
        self.get_logger().info('I heard: "%s"' % msg.data)
        self.heard += 1


def main(args=None):
    rclpy.init(args=args)
    node = MinimalSubscriber()
    print('argv:', ' '.join(sys.argv[1:]), flush=True)
    while rclpy.ok() and node.heard < WANTED:
        rclpy.spin_once(node, timeout_sec=0.1)
    node.destroy_node()
    rclpy.try_shutdown()
"""

LISTENER = """
from rclpy.node import Node
from std_msgs.msg import String


class Listener(Node):

    def __init__(self):
        super().__init__('listener')
        self.heard = 0
        self.sub = self.create_subscription(String, 'chatter', self.chatter_callback, 10)

    def chatter_callback(self, msg):
        print('I heard: [%s]' % msg.data, flush=True)
        self.heard += 1
"""

TALKER = """
from rclpy.node import Node
from std_msgs.msg import String


class Talker(Node):

    def __init__(self):
        super().__init__('talker')
        self.i = 0
        self.pub = self.create_publisher(String, 'chatter', 10)
        self.timer = self.create_timer(0.1, self.timer_callback)

    def timer_callback(self):
        msg = String()
        msg.data = 'Hello World: {0}'.format(self.i)
        self.i += 1
        self.pub.publish(msg)
"""

# A composed process: one module of its own package imported absolutely, one relatively.
COMPOSED = """
import rclpy
from rclpy.executors import SingleThreadedExecutor

from examples_rclpy_executors.listener import Listener
from .talker import Talker


def main(args=None):
    rclpy.init(args=args)
    talker = Talker()
    listener = Listener()
    executor = SingleThreadedExecutor()
    executor.add_node(talker)
    executor.add_node(listener)
    try:
        while rclpy.ok() and listener.heard < 3:
            executor.spin_once(timeout_sec=0.1)
    finally:
        rclpy.try_shutdown()
    print('composed: done')
"""


def examples_clone(ws: Path) -> None:
    """``src/examples/`` as ``git clone https://github.com/ros2/examples`` leaves it (abridged)."""
    rclpy = ws / "src" / "examples" / "rclpy"
    (ws / "src" / "examples" / "README.md").parent.mkdir(parents=True, exist_ok=True)
    (ws / "src" / "examples" / "README.md").write_text("# ROS 2 examples\n")
    python_package(
        rclpy / "topics" / "minimal_publisher",
        "examples_rclpy_minimal_publisher",
        ["publisher_member_function = examples_rclpy_minimal_publisher.publisher_member_function:main"],
        {"publisher_member_function": PUBLISHER},
    )
    python_package(
        rclpy / "topics" / "minimal_subscriber",
        "examples_rclpy_minimal_subscriber",
        ["subscriber_member_function = examples_rclpy_minimal_subscriber.subscriber_member_function:main"],
        {"subscriber_member_function": SUBSCRIBER},
    )
    python_package(
        rclpy / "executors",
        "examples_rclpy_executors",
        [
            "composed = examples_rclpy_executors.composed:main",
            "listener_missing = examples_rclpy_executors.no_such_module:main",
            "talker_missing_function = examples_rclpy_executors.talker:no_such_function",
        ],
        {"listener": LISTENER, "talker": TALKER, "composed": COMPOSED},
    )
