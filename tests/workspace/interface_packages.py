"""Students' interface packages, as ROS 2's "Creating custom msg and srv files" tutorial lays them
out (``tutorial_interfaces``, ament_cmake), a package of richer definitions that nests it, the
action tutorial's ``custom_action_interfaces``, and the tutorials' nodes rewritten to use them,
as ament_python packages."""

from __future__ import annotations

import textwrap
from pathlib import Path

from .action_packages import CLIENT as ACTION_CLIENT
from .action_packages import SERVER as ACTION_SERVER
from .tutorial_packages import python_package, write

INTERFACE_MANIFEST = """\
<?xml version="1.0"?>
<?xml-model href="http://download.ros.org/schema/package_format3.xsd" schematypens="http://www.w3.org/2001/XMLSchema"?>
<package format="3">
  <name>{name}</name>
  <version>0.0.0</version>
  <description>Custom interfaces</description>
  <maintainer email="student@example.com">student</maintainer>
  <license>Apache-2.0</license>

  <buildtool_depend>ament_cmake</buildtool_depend>
  <depend>geometry_msgs</depend>
  <buildtool_depend>rosidl_default_generators</buildtool_depend>
  <exec_depend>rosidl_default_runtime</exec_depend>
  <member_of_group>rosidl_interface_packages</member_of_group>

  <export>
    <build_type>ament_cmake</build_type>
  </export>
</package>
"""

TUTORIAL_CMAKE = """\
cmake_minimum_required(VERSION 3.8)
project(tutorial_interfaces)

find_package(ament_cmake REQUIRED)
find_package(geometry_msgs REQUIRED)
find_package(rosidl_default_generators REQUIRED)

rosidl_generate_interfaces(${PROJECT_NAME}
  "msg/Num.msg"
  "msg/Sphere.msg"
  "srv/AddThreeInts.srv"
  DEPENDENCIES geometry_msgs # Add packages that above messages depend on, in this case geometry_msgs for Sphere.msg
)

ament_package()
"""

NUM = "int64 num\n"
SPHERE = "geometry_msgs/Point center\nfloat64 radius\n"
ADD_THREE_INTS = "int64 a\nint64 b\nint64 c\n---\nint64 sum\n"

# Arrays (fixed, bounded, unbounded), bounded strings, constants, defaults, nested types from
# std_msgs, geometry_msgs and the student's own tutorial_interfaces.
TELEMETRY = """\
# One vehicle's telemetry.
uint8 MODE_IDLE=0
uint8 MODE_FLYING=1
int32 MAX_CODES=4
string CALLSIGN_PREFIX="uav_"

std_msgs/Header header
string<=12 callsign "uav_1"
uint8 mode 1
float64[3] position
int32[<=4] codes
string<=8[] tags
float32[] samples [1.5, 2.5]
tutorial_interfaces/Num[] counts
geometry_msgs/Point[2] corners
"""

FLEET_CMAKE = """\
cmake_minimum_required(VERSION 3.8)
project(fleet_interfaces)

find_package(ament_cmake REQUIRED)
find_package(rosidl_default_generators REQUIRED)
find_package(std_msgs REQUIRED)
find_package(geometry_msgs REQUIRED)
find_package(tutorial_interfaces REQUIRED)

set(msg_files
  "msg/Telemetry.msg"
)
rosidl_generate_interfaces(${PROJECT_NAME}
  ${msg_files}
  DEPENDENCIES std_msgs geometry_msgs tutorial_interfaces
)

ament_package()
"""

# ROS 2's "Creating an action" tutorial: custom_action_interfaces with action/Fibonacci.action.
FIBONACCI = "int32 order\n---\nint32[] sequence\n---\nint32[] partial_sequence\n"
ACTION_CMAKE = """\
cmake_minimum_required(VERSION 3.8)
project(custom_action_interfaces)

find_package(ament_cmake REQUIRED)
find_package(rosidl_default_generators REQUIRED)

rosidl_generate_interfaces(${PROJECT_NAME}
  "action/Fibonacci.action"
)

ament_package()
"""

NUM_PUBLISHER = """
import rclpy
from rclpy.node import Node

from tutorial_interfaces.msg import Num    # CHANGE


class MinimalPublisher(Node):

    def __init__(self):
        super().__init__('minimal_publisher')
        self.publisher_ = self.create_publisher(Num, 'topic', 10)     # CHANGE
        timer_period = 0.2
        self.timer = self.create_timer(timer_period, self.timer_callback)
        self.i = 0

    def timer_callback(self):
        msg = Num()                                                # CHANGE
        msg.num = self.i                                           # CHANGE
        self.publisher_.publish(msg)
        self.get_logger().info('Publishing: "%d"' % msg.num)       # CHANGE
        self.i += 1


def main(args=None):
    try:
        with rclpy.init(args=args):
            minimal_publisher = MinimalPublisher()
            rclpy.spin(minimal_publisher)
    except KeyboardInterrupt:
        pass
"""

NUM_SUBSCRIBER = """
import rclpy
from rclpy.node import Node

from tutorial_interfaces.msg import Num        # CHANGE


class MinimalSubscriber(Node):

    def __init__(self):
        super().__init__('minimal_subscriber')
        self.subscription = self.create_subscription(
            Num,                                               # CHANGE
            'topic',
            self.listener_callback,
            10)
        self.subscription

    def listener_callback(self, msg):
        self.get_logger().info('I heard: "%d"' % msg.num)  # CHANGE


def main(args=None):
    try:
        with rclpy.init(args=args):
            minimal_subscriber = MinimalSubscriber()
            rclpy.spin(minimal_subscriber)
    except KeyboardInterrupt:
        pass
"""

THREE_INTS_SERVICE = """
from tutorial_interfaces.srv import AddThreeInts                                                           # CHANGE

import rclpy
from rclpy.node import Node


class MinimalService(Node):

    def __init__(self):
        super().__init__('minimal_service')
        self.srv = self.create_service(AddThreeInts, 'add_three_ints', self.add_three_ints_callback)       # CHANGE

    def add_three_ints_callback(self, request, response):
        response.sum = request.a + request.b + request.c                                                  # CHANGE
        self.get_logger().info('Incoming request\\na: %d b: %d c: %d' % (request.a, request.b, request.c))  # CHANGE

        return response


def main(args=None):
    try:
        with rclpy.init(args=args):
            minimal_service = MinimalService()
            rclpy.spin(minimal_service)
    except KeyboardInterrupt:
        pass
"""

THREE_INTS_CLIENT = """
import sys

from tutorial_interfaces.srv import AddThreeInts                            # CHANGE
import rclpy
from rclpy.node import Node


class MinimalClientAsync(Node):

    def __init__(self):
        super().__init__('minimal_client_async')
        self.cli = self.create_client(AddThreeInts, 'add_three_ints')       # CHANGE
        while not self.cli.wait_for_service(timeout_sec=1.0):
            self.get_logger().info('service not available, waiting again...')
        self.req = AddThreeInts.Request()                                   # CHANGE

    def send_request(self, a, b, c):
        self.req.a = a
        self.req.b = b
        self.req.c = c                                                      # CHANGE
        return self.cli.call_async(self.req)


def main(args=None):
    with rclpy.init(args=args):
        minimal_client = MinimalClientAsync()
        future = minimal_client.send_request(int(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3]))  # CHANGE
        rclpy.spin_until_future_complete(minimal_client, future)
        response = future.result()
        minimal_client.get_logger().info(
            'Result of add_three_ints: for %d + %d + %d = %d' %                                    # CHANGE
            (minimal_client.req.a, minimal_client.req.b, minimal_client.req.c, response.sum))   # CHANGE
"""

# Publishes Telemetry with every kind of field filled in, then its constants as it sees them.
TELEMETRY_PUBLISHER = """
import rclpy
from rclpy.node import Node
from geometry_msgs.msg import Point

from fleet_interfaces.msg import Telemetry
from tutorial_interfaces.msg import Num


class TelemetryPublisher(Node):

    def __init__(self):
        super().__init__('telemetry_publisher')
        self.publisher_ = self.create_publisher(Telemetry, 'telemetry', 10)
        self.timer = self.create_timer(0.2, self.timer_callback)
        self.i = 0
        self.get_logger().info('modes %d %d, at most %d codes, prefix %s' % (
            Telemetry.MODE_IDLE, Telemetry.MODE_FLYING, Telemetry.MAX_CODES, Telemetry.CALLSIGN_PREFIX))

    def timer_callback(self):
        msg = Telemetry()
        msg.header.frame_id = 'map'
        msg.position = [1.0, 2.0, float(self.i)]
        msg.codes = [7, 8, 9]
        msg.tags = ['red', 'lead']
        msg.counts = [Num(num=self.i), Num(num=-self.i)]
        msg.corners = [Point(x=1.0), Point(y=2.0)]
        self.publisher_.publish(msg)
        self.get_logger().info('Publishing: %d %s mode %d' % (self.i, msg.callsign, msg.mode))
        self.i += 1


def main(args=None):
    try:
        with rclpy.init(args=args):
            rclpy.spin(TelemetryPublisher())
    except KeyboardInterrupt:
        pass
"""

TELEMETRY_SUBSCRIBER = """
import rclpy
from rclpy.node import Node

from fleet_interfaces.msg import Telemetry


class TelemetrySubscriber(Node):

    def __init__(self):
        super().__init__('telemetry_subscriber')
        self.subscription = self.create_subscription(Telemetry, 'telemetry', self.listener_callback, 10)

    def listener_callback(self, msg):
        self.get_logger().info('I heard: %s %s z=%.1f codes=%s tags=%s samples=%s counts=%s corner=%.1f' % (
            msg.header.frame_id, msg.callsign, msg.position[2], msg.codes.tolist(), msg.tags,
            msg.samples.tolist(), [c.num for c in msg.counts], msg.corners[1].y))


def main(args=None):
    try:
        with rclpy.init(args=args):
            rclpy.spin(TelemetrySubscriber())
    except KeyboardInterrupt:
        pass
"""


def interface_package(folder: Path, name: str, cmake: str, files: dict[str, str]) -> None:
    write(folder, {"package.xml": INTERFACE_MANIFEST.format(name=name), "CMakeLists.txt": cmake, **files})


def tutorial_workspace(ws: Path) -> None:
    """``ws/src``: tutorial_interfaces and fleet_interfaces nested below a folder as a clone leaves
    them, and an ament_python package of nodes that use them."""
    interface_package(
        ws / "src/tutorials/tutorial_interfaces",
        "tutorial_interfaces",
        TUTORIAL_CMAKE,
        {
            "msg/Num.msg": NUM,
            "msg/Sphere.msg": SPHERE,
            "srv/AddThreeInts.srv": ADD_THREE_INTS,
        },
    )
    interface_package(
        ws / "src/tutorials/fleet_interfaces",
        "fleet_interfaces",
        FLEET_CMAKE,
        {"msg/Telemetry.msg": TELEMETRY},
    )
    interface_package(
        ws / "src/tutorials/custom_action_interfaces",
        "custom_action_interfaces",
        ACTION_CMAKE,
        {"action/Fibonacci.action": FIBONACCI},
    )
    students = "from custom_action_interfaces.action import Fibonacci"
    action_nodes = {"fibonacci_server": ACTION_SERVER, "fibonacci_client": ACTION_CLIENT}
    modules = {
        "publisher_member_function": NUM_PUBLISHER,
        "subscriber_member_function": NUM_SUBSCRIBER,
        "service_member_function": THREE_INTS_SERVICE,
        "client_member_function": THREE_INTS_CLIENT,
        "telemetry_publisher": TELEMETRY_PUBLISHER,
        "telemetry_subscriber": TELEMETRY_SUBSCRIBER,
        **{
            m: t.replace("from action_tutorials_interfaces.action import Fibonacci", students)
            for m, t in action_nodes.items()
        },
    }
    scripts = [
        f"{short} = py_custom.{module}:main"
        for short, module in [
            ("talker", "publisher_member_function"),
            ("listener", "subscriber_member_function"),
            ("service", "service_member_function"),
            ("client", "client_member_function"),
            ("telemetry_talker", "telemetry_publisher"),
            ("telemetry_listener", "telemetry_subscriber"),
            ("fibonacci_server", "fibonacci_server"),
            ("fibonacci_client", "fibonacci_client"),
        ]
    ]
    python_package(
        ws / "src/py_custom", "py_custom", scripts, {m: textwrap.dedent(t) for m, t in modules.items()}
    )
