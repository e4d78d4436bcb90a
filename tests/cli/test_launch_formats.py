"""``ros2lab launch PKG FILE`` with launch files in Python, XML and YAML: the docs' "Integrating
launch files into ROS 2 packages" file in its three forms, and "Using substitutions"-style
arguments and includes, start a workspace package's node with the name, namespace and remapped
topic the file asks for (as ``ros2lab node list`` and ``topic list`` show); a broken launch file
is one line naming its file and line."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import pytest

from .conftest import LiveServer, Result, Running

PACKAGE = "fmt_demo"
PACKAGE_XML = f"""<?xml version="1.0"?>
<package format="3">
  <name>{PACKAGE}</name>
  <version>0.0.0</version>
  <description>launch files in three formats</description>
  <maintainer email="student@example.com">student</maintainer>
  <license>MIT</license>
  <exec_depend>rclpy</exec_depend>
  <export><build_type>ament_python</build_type></export>
</package>
"""
SETUP_PY = f"""from setuptools import setup

package_name = '{PACKAGE}'

setup(
    name=package_name,
    packages=[package_name],
    entry_points={{
        'console_scripts': [
            'talker = {PACKAGE}.talker:main',
        ],
    }},
)
"""
TALKER = """import rclpy
from rclpy.node import Node
from std_msgs.msg import String


class Talker(Node):
    def __init__(self):
        super().__init__('talker')
        self.pub = self.create_publisher(String, 'chatter', 10)
        self.create_timer(0.2, lambda: self.pub.publish(String(data='hello')))
        self.get_logger().info('talking')


def main():
    rclpy.init()
    rclpy.spin(Talker())
"""
LAUNCH_FILES = {
    "talker.launch.py": """import launch
import launch_ros.actions


def generate_launch_description():
    return launch.LaunchDescription([
        launch_ros.actions.Node(
            package='fmt_demo',
            executable='talker',
            name='talker',
            namespace='fmt_py',
            remappings=[('chatter', 'announcements')]),
    ])
""",
    "talker_launch.xml": """<launch>
  <node pkg="fmt_demo" exec="talker" name="talker" namespace="fmt_xml">
    <remap from="chatter" to="announcements"/>
  </node>
</launch>
""",
    "talker_launch.yaml": """launch:

- node:
    pkg: "fmt_demo"
    exec: "talker"
    name: "talker"
    namespace: "fmt_yaml"
    remap:
    - from: "chatter"
      to: "announcements"
""",
    "example_main.launch.py": """from launch_ros.substitutions import FindPackageShare

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, IncludeLaunchDescription, LogInfo
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.substitutions import LaunchConfiguration, PathJoinSubstitution, TextSubstitution


def generate_launch_description():
    return LaunchDescription([
        DeclareLaunchArgument('outer_ns', default_value='subst_default'),
        LogInfo(msg=['namespace is ', LaunchConfiguration('outer_ns')]),
        IncludeLaunchDescription(
            PythonLaunchDescriptionSource([
                PathJoinSubstitution([FindPackageShare('fmt_demo'), 'launch', 'example_talker.launch.py'])
            ]),
            launch_arguments={
                'talker_ns': LaunchConfiguration('outer_ns'),
                'topic': TextSubstitution(text='news'),
            }.items()
        ),
    ])
""",
    "example_talker.launch.py": """from launch_ros.actions import Node

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration


def generate_launch_description():
    return LaunchDescription([
        DeclareLaunchArgument('talker_ns', default_value='talkers'),
        DeclareLaunchArgument('topic', default_value='chatter'),
        Node(package='fmt_demo', executable='talker', name='talker',
             namespace=LaunchConfiguration('talker_ns'),
             remappings=[('chatter', LaunchConfiguration('topic'))]),
    ])
""",
    "broken.launch.py": """from launch import LaunchDescription


def generate_launch_description():
    return LaunchDescription([1 / 0])
""",
}


@pytest.fixture(scope="module")
def package(live_server: LiveServer) -> Path:
    """The package, in the live server's workspace (its ``./workspace``)."""
    root = live_server.log_path.parent / "workspace" / "src" / PACKAGE
    (root / PACKAGE).mkdir(parents=True, exist_ok=True)
    (root / "launch").mkdir(exist_ok=True)
    (root / "package.xml").write_text(PACKAGE_XML)
    (root / "setup.py").write_text(SETUP_PY)
    (root / PACKAGE / "__init__.py").write_text("")
    (root / PACKAGE / "talker.py").write_text(TALKER)
    for name, text in LAUNCH_FILES.items():
        (root / "launch" / name).write_text(text)
    return root


def node_names(server: LiveServer) -> set[str]:
    return {n["name"] for n in server.get("/api/nodes")}


def launched(
    server: LiveServer,
    start: Callable[..., Running],
    ros2lab: Callable[..., Result],
    node: str,
    topic: str,
    *args: str,
) -> Running:
    """``ros2lab launch fmt_demo ARGS``, once its node is in the graph and ``node list`` and
    ``topic list`` name it and its topic."""
    launching = start("launch", PACKAGE, *args)
    launching.read_until(lambda line: line == f"[INFO] [launch]: process started: /talker ({PACKAGE} talker)")
    logger = node.lstrip("/").replace("/", ".")  # rcl's logger name: the namespace and name, dotted
    launching.read_until(lambda line: line.endswith(f"[{logger}]: talking"), timeout_s=30.0)
    server.wait_until(lambda: node in node_names(server), f"{node} in the graph", 20.0)
    server.wait_until(
        lambda: topic in {t["name"] for t in server.get("/api/topics")}, f"{topic} listed", 20.0
    )
    nodes, topics = ros2lab("node", "list"), ros2lab("topic", "list")
    assert nodes.code == 0 and node in nodes.out.splitlines(), nodes
    assert topics.code == 0 and topic in topics.out.splitlines(), topics
    return launching


@pytest.mark.parametrize(
    ("file", "namespace"),
    [("talker.launch.py", "fmt_py"), ("talker_launch.xml", "fmt_xml"), ("talker_launch.yaml", "fmt_yaml")],
)
def test_launch_file_in_each_format_starts_the_named_namespaced_remapped_node(
    live_server: LiveServer,
    package: Path,
    start: Callable[..., Running],
    ros2lab: Callable[..., Result],
    file: str,
    namespace: str,
) -> None:
    launching = launched(
        live_server, start, ros2lab, f"/{namespace}/talker", f"/{namespace}/announcements", file
    )
    topics = ros2lab("topic", "list").out.splitlines()
    assert f"/{namespace}/chatter" not in topics, topics  # remapped, so never advertised
    code, err = launching.interrupt()
    assert (code, err) == (0, ""), err
    live_server.wait_until(lambda: f"/{namespace}/talker" not in node_names(live_server), "the talker gone")


def test_substitutions_arguments_and_includes_give_namespace_and_topic(
    live_server: LiveServer, package: Path, start: Callable[..., Running], ros2lab: Callable[..., Result]
) -> None:
    launching = launched(
        live_server,
        start,
        ros2lab,
        "/from_cli/talker",
        "/from_cli/news",
        "example_main.launch.py",
        "outer_ns:=from_cli",
    )
    assert "[INFO] [launch.user]: namespace is from_cli" in launching.seen
    code, err = launching.interrupt()
    assert (code, err) == (0, ""), err


def test_a_broken_python_launch_file_is_one_line_naming_it(
    package: Path, ros2lab: Callable[..., Result]
) -> None:
    result = ros2lab("launch", PACKAGE, "broken.launch.py")

    assert result.code == 1, result
    path = package / "launch" / "broken.launch.py"
    assert result.err.splitlines() == [f"error: {path.resolve()}:5: ZeroDivisionError: division by zero"], (
        result.err
    )
