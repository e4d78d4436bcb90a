"""Python launch files (``.launch.py``) evaluated in a process of their own into the launch model:
ROS 2's launch and launch_ros API as the docs' tutorials use it, includes across the three
front-ends, and a student's mistakes as one line naming the file and line."""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest

from node_runtime.ament.index import PackageIndex
from node_runtime.bus import ManualClock
from server.__main__ import build_parser, check_launch, settings_of, zenoh_settings
from server.host.settings import LabSettings, Settings
from server.services.launch.description import LaunchDescription, LaunchFileError
from server.services.launch.launcher import parse_launch
from server.services.launch.python_launch import MAX_MESSAGE_CHARS, MAX_MESSAGES
from server.world.lab import Lab

PACKAGE_XML = """<?xml version="1.0"?>
<package format="3">
  <name>demo_launch</name>
  <version>0.0.0</version>
  <description>launch files</description>
  <maintainer email="a@b.c">a</maintainer>
  <license>MIT</license>
  <export><build_type>ament_python</build_type></export>
</package>
"""
# "Using substitutions": the included file, as the page writes it (turtlesim's node aside).
SUBSTITUTIONS = """
from launch_ros.actions import Node

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, ExecuteProcess, TimerAction
from launch.conditions import IfCondition
from launch.substitutions import LaunchConfiguration, PythonExpression


def generate_launch_description():
    turtlesim_ns = LaunchConfiguration('turtlesim_ns')
    use_provided_red = LaunchConfiguration('use_provided_red')
    new_background_r = LaunchConfiguration('new_background_r')

    turtlesim_ns_launch_arg = DeclareLaunchArgument('turtlesim_ns', default_value='turtlesim1')
    use_provided_red_launch_arg = DeclareLaunchArgument('use_provided_red', default_value='False')
    new_background_r_launch_arg = DeclareLaunchArgument('new_background_r', default_value='200')

    turtlesim_node = Node(
        package='turtlesim',
        namespace=turtlesim_ns,
        executable='turtlesim_node',
        name='sim'
    )
    change_background_r_conditioned = ExecuteProcess(
        condition=IfCondition(
            PythonExpression([new_background_r, ' == 200', ' and ', use_provided_red])
        ),
        cmd=[['ros2 param set ', turtlesim_ns, '/sim background_r ', new_background_r]],
        shell=True
    )
    listener_conditioned = Node(
        condition=IfCondition(PythonExpression([new_background_r, ' == 200 and ', use_provided_red])),
        package='demo_launch', executable='listener', namespace=turtlesim_ns,
    )
    return LaunchDescription([
        turtlesim_ns_launch_arg,
        use_provided_red_launch_arg,
        new_background_r_launch_arg,
        turtlesim_node,
        TimerAction(period=2.0, actions=[change_background_r_conditioned, listener_conditioned]),
    ])
"""
# "Using substitutions": the file that includes it.
MAIN = """
from launch_ros.substitutions import FindPackageShare

from launch import LaunchDescription
from launch.actions import IncludeLaunchDescription
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.substitutions import PathJoinSubstitution, TextSubstitution


def generate_launch_description():
    colors = {
        'background_r': '200'
    }

    return LaunchDescription([
        IncludeLaunchDescription(
            PythonLaunchDescriptionSource([
                PathJoinSubstitution([
                    FindPackageShare('demo_launch'),
                    'launch',
                    'example_substitutions.launch.py'
                ])
            ]),
            launch_arguments={
                'turtlesim_ns': 'turtlesim2',
                'use_provided_red': 'True',
                'new_background_r': TextSubstitution(text=str(colors['background_r']))
            }.items()
        )
    ])
"""


@pytest.fixture
def package(tmp_path: Path) -> Path:
    """A workspace's ament_python package ``demo_launch``; its ``launch/`` folder is returned."""
    root = tmp_path / "ws" / "src" / "demo_launch"
    (root / "launch").mkdir(parents=True)
    (root / "config").mkdir()
    (root / "package.xml").write_text(PACKAGE_XML)
    (root / "setup.py").write_text("from setuptools import setup\nsetup(name='demo_launch')\n")
    return root / "launch"


def write(folder: Path, name: str, text: str) -> Path:
    path = folder / name
    path.write_text(textwrap.dedent(text).lstrip())
    return path


def launch(path: Path, **args: str) -> LaunchDescription:
    return parse_launch(path, args, PackageIndex(workspace=path.parents[3]))


def test_using_substitutions_include_arguments_conditions_and_namespaces(package: Path) -> None:
    write(package, "example_substitutions.launch.py", SUBSTITUTIONS)
    main = write(package, "example_main.launch.py", MAIN)

    description = launch(main)

    sim, listener = description.nodes
    assert (sim.pkg, sim.exec, sim.name, sim.namespace) == (
        "turtlesim",
        "turtlesim_node",
        "sim",
        "/turtlesim2",
    )
    assert (listener.exec, listener.namespace) == ("listener", "/turtlesim2")  # 200 == 200 and True
    assert [Path(f).name for f in description.files] == [
        "example_main.launch.py",
        "example_substitutions.launch.py",
    ]
    assert (Path(sim.location.file).name, sim.location.line) == ("example_substitutions.launch.py", 18)
    (command,) = description.commands  # the ExecuteProcess, its condition true, in the TimerAction
    assert (command.cmd, command.shell, command.name, command.output, command.start_delay_s) == (
        ("ros2 param set turtlesim2/sim background_r 200",),
        True,
        None,
        "log",
        2.0,
    )
    assert (Path(command.location.file).name, command.location.line) == (
        "example_substitutions.launch.py",
        24,
    )
    assert (sim.start_delay_s, listener.start_delay_s) == (0.0, 2.0)  # the TimerAction's period
    alone = launch(package / "example_substitutions.launch.py", new_background_r="100")
    assert [(n.name, n.namespace) for n in alone.nodes] == [("sim", "/turtlesim1")]  # the condition false
    assert alone.commands == ()
    assert dict(alone.args) == {
        "turtlesim_ns": "turtlesim1",
        "use_provided_red": "False",
        "new_background_r": "100",
    }


def test_groups_scope_namespace_remaps_and_parameters(package: Path) -> None:
    path = write(
        package,
        "groups.launch.py",
        """
        import os
        from ament_index_python.packages import get_package_share_directory
        from launch import LaunchDescription
        from launch.actions import GroupAction, LogInfo, SetLaunchConfiguration
        from launch.substitutions import EnvironmentVariable, LaunchConfiguration
        from launch_ros.actions import Node, PushRosNamespace, SetParameter, SetRemap


        def generate_launch_description():
            params = os.path.join(get_package_share_directory('demo_launch'), 'config', 'params.yaml')
            return LaunchDescription([
                SetLaunchConfiguration('who', 'outer'),
                GroupAction([
                    PushRosNamespace('robot'),
                    SetRemap(src='chatter', dst='announcements'),
                    SetParameter(name='use_sim_time', value=True),
                    SetLaunchConfiguration('who', 'inner'),
                    Node(package='demo_launch', executable='talker', name=LaunchConfiguration('who'),
                         namespace='arm', parameters=[{'rate': {'hz': 5}, 'names': ['a', 'b']}, params],
                         remappings=[('chatter', 'ignored'), ('other', 'mine')], arguments=['--x'],
                         ros_arguments=['--log-level', 'debug'], output='screen'),
                ]),
                Node(package='demo_launch', executable='talker', name=LaunchConfiguration('who'),
                     namespace='/absolute'),
                LogInfo(msg=['home is ', EnvironmentVariable('NO_SUCH_VARIABLE', default_value='unset')]),
            ])
        """,
    )
    (package.parent / "config" / "params.yaml").write_text("/**:\n  ros__parameters:\n    from_file: 7\n")

    inner, outer = launch(path).nodes

    assert (inner.name, inner.namespace, inner.output) == ("inner", "/robot/arm", "screen")
    assert inner.parameters == (("use_sim_time", True), ("rate.hz", 5), ("names", ["a", "b"]))
    assert [Path(f.path).name for f in inner.parameter_files] == ["params.yaml"]
    # rcl takes the first rule for a name: the group's SetRemap before the node's own.
    assert inner.remappings == (("chatter", "announcements"), ("other", "mine"))
    assert (inner.arguments, inner.ros_arguments) == (("--x",), ("--log-level", "debug"))
    assert (outer.name, outer.namespace, outer.parameters, outer.remappings) == ("outer", "/absolute", (), ())
    assert launch(path).messages == ("[INFO] [launch.user]: home is unset",)


def test_python_xml_and_yaml_include_each_other(package: Path) -> None:
    write(
        package,
        "leaf.launch.py",
        """
        from launch import LaunchDescription
        from launch.actions import DeclareLaunchArgument
        from launch.substitutions import LaunchConfiguration
        from launch_ros.actions import Node

        def generate_launch_description():
            return LaunchDescription([DeclareLaunchArgument('exe'),
                                      Node(package='demo_launch', executable=LaunchConfiguration('exe'))])
        """,
    )
    write(
        package,
        "middle_launch.xml",
        """
        <launch>
          <arg name="exe"/>
          <include file="$(dirname)/leaf.launch.py"><arg name="exe" value="$(var exe)_via_xml"/></include>
        </launch>
        """,
    )
    write(
        package,
        "middle_launch.yaml",
        """
        launch:
        - arg: {name: exe}
        - arg: {name: suffix, default: ""}
        - node: {pkg: demo_launch, exec: "$(var exe)_in_yaml$(var suffix)"}
        """,
    )
    top = write(
        package,
        "top.launch.py",
        """
        from launch import LaunchDescription
        from launch.actions import GroupAction, IncludeLaunchDescription
        from launch.launch_description_sources import AnyLaunchDescriptionSource
        from launch.substitutions import ThisLaunchFileDir
        from launch_ros.actions import PushRosNamespace
        from launch_xml.launch_description_sources import XMLLaunchDescriptionSource

        def generate_launch_description():
            return LaunchDescription([
                GroupAction([
                    PushRosNamespace('ns'),
                    IncludeLaunchDescription(XMLLaunchDescriptionSource([ThisLaunchFileDir(), '/middle_launch.xml']),
                                             launch_arguments={'exe': 'a'}.items()),
                ]),
                IncludeLaunchDescription(AnyLaunchDescriptionSource([ThisLaunchFileDir(), '/middle_launch.yaml']),
                                         launch_arguments=[('exe', 'b')]),
            ])
        """,
    )

    description = launch(top)

    assert [(n.exec, n.namespace) for n in description.nodes] == [("a_via_xml", "/ns"), ("b_in_yaml", None)]
    names = [Path(f).name for f in description.files]
    assert names == ["top.launch.py", "middle_launch.xml", "leaf.launch.py", "middle_launch.yaml"]
    # As ros2 launch sets them, arguments given reach an included file that declares them.
    assert [n.exec for n in launch(top, suffix="_given").nodes] == ["a_via_xml", "b_in_yaml_given"]
    with pytest.raises(LaunchFileError) as caught:
        launch(top, sufix="_given")
    assert (
        "argument 'sufix' was given but the launch declares no such argument; did you mean 'suffix'?"
        in str(caught.value)
    )


BROKEN = {
    "forged.launch.py": (  # the answer is a student's code's: not trusted
        "import os\n\ndef generate_launch_description():\n"
        '    os.write(1, b\'{"found": [{"kind": "node", "pkg": "p", "exec": "x", '
        '"line": "not a line"}]}\\n\')\n    os._exit(0)\n',
        0,
        "its evaluation did not answer a launch description",
    ),
    "raises.launch.py": (
        "from launch import LaunchDescription\n\ndef generate_launch_description():\n    return 1 / 0\n",
        4,
        "ZeroDivisionError: division by zero",
    ),
    "returns_list.launch.py": (
        "def generate_launch_description():\n    return []\n",
        0,
        "generate_launch_description() returned list, not a launch.LaunchDescription",
    ),
    "nothing.launch.py": ("X = 1\n", 0, "it has no generate_launch_description() function"),
    "syntax.launch.py": ("def generate_launch_description(:\n    pass\n", 1, "SyntaxError"),
    "unknown_pkg.launch.py": (
        "from launch import LaunchDescription\nfrom launch.actions import IncludeLaunchDescription\n"
        "from launch_ros.substitutions import FindPackageShare\n\ndef generate_launch_description():\n"
        "    return LaunchDescription([\n        IncludeLaunchDescription([FindPackageShare('no_such_pkg'), "
        "'/launch/x.launch.py'])])\n",
        7,
        "package 'no_such_pkg' not found",
    ),
    "unknown_share.launch.py": (
        "from ament_index_python.packages import get_package_share_directory\n\n"
        "def generate_launch_description():\n    get_package_share_directory('no_such_pkg')\n",
        4,
        "PackageNotFoundError: \"package 'no_such_pkg' not found",
    ),
    "undeclared.launch.py": (
        "from launch import LaunchDescription\nfrom launch_ros.actions import Node\n"
        "from launch.substitutions import LaunchConfiguration\n\ndef generate_launch_description():\n"
        "    return LaunchDescription([Node(package='p', executable=LaunchConfiguration('robto'))])\n",
        6,
        "launch configuration 'robto' does not exist",
    ),
    "condition.launch.py": (
        "from launch import LaunchDescription\nfrom launch.actions import LogInfo\n"
        "from launch.conditions import IfCondition\n\ndef generate_launch_description():\n"
        "    return LaunchDescription([LogInfo(msg='x', condition=IfCondition('maybe'))])\n",
        6,
        "the condition 'maybe' is not a boolean",
    ),
}


@pytest.mark.parametrize("name", sorted(BROKEN))
def test_a_broken_launch_file_is_one_line_naming_file_and_line(package: Path, name: str) -> None:
    text, line, problem = BROKEN[name]
    path = write(package, name, text)

    with pytest.raises(LaunchFileError) as caught:
        launch(path)

    error = caught.value
    assert (Path(error.file), error.line) == (path.resolve(), line), str(error)
    assert problem in error.problem and "Traceback" not in error.problem and "\n" not in error.problem


def test_arguments_given_must_be_declared_and_required_ones_given(package: Path) -> None:
    write(package, "example_substitutions.launch.py", SUBSTITUTIONS)
    with pytest.raises(LaunchFileError) as caught:
        launch(package / "example_substitutions.launch.py", turtlesim_nss="x")
    assert (
        "argument 'turtlesim_nss' was given but the launch declares no such argument; "
        "did you mean 'turtlesim_ns'?" in caught.value.problem
    )
    path = write(
        package,
        "required.launch.py",
        """
        from launch import LaunchDescription
        from launch.actions import DeclareLaunchArgument

        def generate_launch_description():
            return LaunchDescription([DeclareLaunchArgument('robot', description='which robot')])
        """,
    )
    with pytest.raises(LaunchFileError) as caught:
        launch(path)
    assert (caught.value.line, caught.value.problem) == (
        5,
        "required launch argument 'robot' (description: 'which robot') was not provided: give it as NAME:=VALUE",
    )


def test_a_timer_actions_nodes_start_after_its_period_unless_stopped_first(tmp_path: Path) -> None:
    path = tmp_path / "timed.launch.py"
    write(
        tmp_path,
        "timed.launch.py",
        """
        from launch import LaunchDescription
        from launch.actions import TimerAction
        from launch_ros.actions import Node

        def generate_launch_description():
            return LaunchDescription([
                Node(package='rocketship', executable='countdown', name='at_once'),
                TimerAction(period=2.0, actions=[Node(package='rocketship', executable='countdown', name='later')]),
            ])
        """,
    )
    lab = Lab(Settings(lab=LabSettings(launch="rocket", viewer=False, workspace=None)), ManualClock(0.0))
    lab.start_nodes()

    lab.launch_groups.launch(path, {})
    lab.executor.spin_until(1.9)
    assert {"/at_once"} <= {n.fully_qualified_name for n in lab.bus.nodes}
    assert "/later" not in {n.fully_qualified_name for n in lab.bus.nodes}
    lab.executor.spin_until(2.1)
    assert "/later" in {n.fully_qualified_name for n in lab.bus.nodes}

    second = lab.launch_groups.launch(path, {})  # stopped before its timer fires: "later" never starts
    lab.launch_groups.stop(second.id)
    before = len(lab.bus.nodes)
    lab.executor.spin_until(5.0)
    assert len(lab.bus.nodes) == before
    lab.launcher.shutdown()


def server_settings(*argv: str) -> Settings:
    args = build_parser().parse_args(list(argv))
    return settings_of(args, zenoh_settings(args))


def test_a_class_servers_python_launch_outside_the_sandboxs_view_is_refused_at_start(tmp_path: Path) -> None:
    """A class server evaluates a .launch.py in its worlds' sandbox, which sees the lab's packages
    and the world's workspace only: the server's own --launch elsewhere is one line at start, and a
    single lab (no sandbox) takes the same file."""
    path = write(
        tmp_path,
        "world.launch.py",
        "from launch import LaunchDescription\n\n"
        "def generate_launch_description():\n    return LaunchDescription([])\n",
    )
    args = ["--launch", str(path), "--no-foxglove"]

    problem = check_launch(server_settings("--classroom", "--class-code", "ABC123", *args))

    assert problem is not None and problem.startswith(
        f"{path}:0: a Python launch file runs in the students' sandbox"
    )
    assert check_launch(server_settings(*args)) is None


def test_what_a_launch_file_says_is_kept_to_a_bounded_size(package: Path) -> None:
    path = write(
        package,
        "chatty.launch.py",
        """
        from launch import LaunchDescription
        from launch.actions import LogInfo

        def generate_launch_description():
            return LaunchDescription([LogInfo(msg=f'line {i} ' + 'x' * 5000) for i in range(300)])
        """,
    )

    messages = launch(path).messages

    assert len(messages) == MAX_MESSAGES and messages[0].startswith("[INFO] [launch.user]: line 0 xxx")
    assert {len(m) for m in messages} == {MAX_MESSAGE_CHARS}
