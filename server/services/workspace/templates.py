"""The lab's starting files, offered by the editor as templates: skeletons of the nodes the lab
asks for, in this project's own words, with ``# TODO`` where the student's code goes. ``{package}``
in a template's path and text stands for the package it goes in."""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Any


@dataclass(frozen=True)
class Template:
    name: str
    title: str
    description: str
    path: str  # a suggested path in the workspace
    text: str

    def describe(self) -> dict[str, Any]:
        return asdict(self)


_MAIN = """

def main():
    rclpy.init()
    node = {cls}()
    try:
        rclpy.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass  # Ctrl-C (the page's Stop) ends the node quietly
    finally:
        node.destroy_node()
        rclpy.try_shutdown()


if __name__ == '__main__':
    main()
"""

ROCKET_KEYS = '''import rclpy
from keyboard_msgs.msg import Key
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from std_msgs.msg import Bool


class KeyboardManager(Node):
    """Turns the page's key presses into the rocket's abort signal."""

    def __init__(self):
        super().__init__('KeyboardManager')
        self.last_key = None
        self.abort = Bool(data=False)
        # TODO: subscribe to /keydown (keyboard_msgs/msg/Key) with self.on_key as the callback
        # TODO: make a publisher of std_msgs/msg/Bool on /abort_takeoff
        # TODO: call self.tick ten times a second with a timer

    def on_key(self, msg):
        self.last_key = msg.code

    def tick(self):
        # TODO: once the "a" key (Key.KEY_A) was pressed, keep self.abort.data True
        # TODO: publish self.abort on every tick, then forget the key
        pass
''' + _MAIN.format(cls="KeyboardManager")

DRONE_KEYS = '''import rclpy
from geometry_msgs.msg import Vector3
from keyboard_msgs.msg import Key
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node


class KeyboardManager(Node):
    """Moves the drone's position setpoint one metre per arrow key."""

    def __init__(self):
        super().__init__('keyboard_manager_node')
        self.last_key = None
        self.setpoint = Vector3(x=0.0, y=0.0, z=3.0)  # where the drone hovers at first, in metres
        self.get_logger().info('keyboard manager ready: arrow keys move the drone')
        # TODO: subscribe to /keydown (keyboard_msgs/msg/Key) with self.on_key as the callback
        # TODO: make a publisher of geometry_msgs/msg/Vector3 on /uav/input/position
        # TODO: call self.tick twenty times a second with a timer

    def on_key(self, msg):
        self.last_key = msg.code

    def tick(self):
        # TODO: right/left arrow (Key.KEY_RIGHT, Key.KEY_LEFT): x one metre up or down;
        #       up/down arrow (Key.KEY_UP, Key.KEY_DOWN): y one metre up or down
        # TODO: publish self.setpoint, then forget the key
        pass
''' + _MAIN.format(cls="KeyboardManager")

POSITION_PUBLISHER = '''import rclpy
from geometry_msgs.msg import Vector3
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node


class PositionPublisher(Node):
    """Sends the drone one goal position, once a second."""

    def __init__(self):
        super().__init__('position_publisher')
        self.goal = Vector3(x=5.0, y=5.0, z=10.0)  # metres
        # TODO: make a publisher of geometry_msgs/msg/Vector3 on /uav/input/position
        # TODO: call self.tick once a second with a timer

    def tick(self):
        # TODO: publish self.goal and log it with self.get_logger().info(...)
        pass
''' + _MAIN.format(cls="PositionPublisher")

FLY_LAUNCH = """<?xml version="1.0"?>
<!-- The drone's simulator, the page's keyboard and your keyboard manager, in one launch. -->
<launch>
  <include file="$(find-pkg-share visualizer)/launch/view.launch"/>
  <include file="$(find-pkg-share flightcontroller)/launch/position.launch"/>
  <include file="$(find-pkg-share flightcontroller)/launch/velocity.launch"/>
  <include file="$(find-pkg-share flightcontroller)/launch/angle.launch"/>
  <include file="$(find-pkg-share sensor_simulation)/launch/sensors.launch"/>
  <node pkg="flightgoggles" exec="flightgoggles_uav_dynamics" name="flightgoggles_uav_dynamics" output="screen"/>
  <node pkg="keyboard" exec="keyboard" name="keyboard" output="screen"/>
  <!-- TODO: start your keyboard manager: pkg="{package}" and exec= the executable's name -->
</launch>
"""

TEMPLATES = (
    Template(
        "rocket_keyboard_manager",
        "Keyboard manager (part 1: the rocket)",
        "Publishes /abort_takeoff as true from the first press of the a key on.",
        "src/{package}/{package}/keyboard_manager.py",
        ROCKET_KEYS,
    ),
    Template(
        "drone_keyboard_manager",
        "Keyboard manager (part 2: the drone)",
        "Moves the position setpoint on /uav/input/position one metre per arrow key.",
        "src/{package}/{package}/keyboard_manager.py",
        DRONE_KEYS,
    ),
    Template(
        "position_publisher",
        "Position publisher (1 Hz)",
        "Publishes one goal on /uav/input/position once a second.",
        "src/{package}/{package}/position_publisher.py",
        POSITION_PUBLISHER,
    ),
    Template(
        "fly_launch",
        "Launch file: simulator, keyboard and keyboard manager",
        "Starts the drone's simulator and controllers, the keyboard node and your keyboard manager.",
        "src/{package}/launch/fly.launch",
        FLY_LAUNCH,
    ),
)
