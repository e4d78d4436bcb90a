"""docs.ros.org's launch tutorials, whole: a workspace whose packages ``ros2lab pkg create`` made and
the student then wrote as the pages say (tests/workspace/launch_tutorials.py), started with
``ros2lab launch PKG FILE`` on a live lab and checked as the pages check them: the nodes' lines,
``ros2lab node list`` and ``ros2lab topic list``. "Using substitutions" runs in Python and YAML, its
commands (``ros2 service call``, ``ros2 param set``, one after a 2 s timer) as the lab's CLI: the
turtle they spawn and the background they set are checked too."""

from __future__ import annotations

import subprocess
from collections.abc import Iterator
from pathlib import Path

import pytest
from processes.node_process import NodeProcess
from support.app import App
from support.forked_cli import cli_command
from support.wait import wait_until

from .launch_tutorials import (
    EXAMPLE_MAIN,
    EXAMPLE_SUBSTITUTIONS,
    MIMIC,
    MY_SCRIPT,
    PARAM_LAUNCH,
    PARAM_NODE,
    edit_setup_py,
    write_files,
)

CLI_S = 60.0
STAMP = r"\[\d+\.\d{9}\]"


def ros2lab(*args: str, cwd: Path | None = None) -> tuple[int, str, str]:
    done = subprocess.run(
        cli_command(*args),
        capture_output=True,
        text=True,
        timeout=CLI_S,
        check=False,
        cwd=cwd,
    )
    return done.returncode, done.stdout, done.stderr


def create_package(src: Path, name: str) -> Path:
    """``ros2 pkg create --build-type ament_python --license Apache-2.0 NAME`` in ``src``, as each page
    starts (python_parameters with ``--dependencies rclpy``)."""
    extra = ["--dependencies", "rclpy"] if name == "python_parameters" else []
    code, _out, err = ros2lab(
        "pkg", "create", "--build-type", "ament_python", "--license", "Apache-2.0", name, *extra, cwd=src
    )
    assert code == 0, err
    return src / name


def tutorial_workspace(ws: Path) -> None:
    src = ws / "src"
    src.mkdir(parents=True)
    params = create_package(src, "python_parameters")
    edit_setup_py(params, ("minimal_param_node = python_parameters.python_parameters_node:main",))
    write_files(
        params,
        {
            "python_parameters/python_parameters_node.py": PARAM_NODE,
            "launch/python_parameters_launch.py": PARAM_LAUNCH,
        },
    )
    example = create_package(src, "py_launch_example")
    edit_setup_py(example)
    write_files(example, {f"launch/my_script_launch.{kind}": text for kind, text in MY_SCRIPT.items()})
    tutorial = create_package(src, "launch_tutorial")
    edit_setup_py(tutorial)
    write_files(tutorial, {f"launch/example_main_launch.{kind}": text for kind, text in EXAMPLE_MAIN.items()})
    write_files(ws, {f"launch/turtlesim_mimic_launch.{kind}": text for kind, text in MIMIC.items()})
    write_files(
        tutorial,
        {f"launch/example_substitutions_launch.{kind}": text for kind, text in EXAMPLE_SUBSTITUTIONS.items()},
    )


@pytest.fixture(scope="module")
def ws(tmp_path_factory: pytest.TempPathFactory) -> Path:
    ws = tmp_path_factory.mktemp("launch_tutorials") / "ros2_ws"
    tutorial_workspace(ws)
    return ws


@pytest.fixture(scope="module")
def lab(ws: Path) -> Iterator[App]:
    root = ws.parent
    (root / "nothing.launch.xml").write_text("<launch/>\n")
    app = App(
        root, "--launch", str(root / "nothing.launch.xml"), "--workspace", str(root / "ros2_ws"), cwd=root
    )
    try:
        yield app
    finally:
        app.stop()


@pytest.fixture
def launch(lab: App, tmp_path: Path) -> Iterator[type[NodeProcess]]:
    """``ros2lab launch PKG FILE`` left running; each is stopped with Ctrl-C (its nodes with it)."""
    started: list[NodeProcess] = []

    class Launched(NodeProcess):
        def __init__(self, *arguments: str) -> None:
            command = cli_command("--url", lab.url, "launch", *arguments)
            super().__init__(
                lab,
                tmp_path / Path(arguments[1] if len(arguments) > 1 else arguments[0]).name,
                command=command,
            )
            started.append(self)

        def stop(self) -> None:
            assert self.interrupt() == 0, self.text[-3000:]
            assert "Traceback" not in self.text, self.text[-3000:]

    yield Launched
    for proc in started:
        proc.kill()


def graph(lab: App, verb: str) -> set[str]:
    code, out, err = ros2lab("--url", lab.url, verb, "list")
    assert code == 0, err
    return set(out.splitlines())


@pytest.mark.parametrize("kind", ["py", "yaml"])
def test_creating_a_launch_file_turtle2_mimics_turtle1(
    lab: App, ws: Path, launch: type[NodeProcess], tmp_path: Path, kind: str
) -> None:
    launched = launch(str(ws / "launch" / f"turtlesim_mimic_launch.{kind}"))
    launched.wait_for(r"Starting turtlesim with node name /turtlesim2/sim$")
    assert {"/turtlesim1/sim", "/turtlesim2/sim", "/mimic"} <= graph(lab, "node")
    cli = cli_command("--url", lab.url)
    echo = [*cli, "topic", "echo", "/turtlesim2/turtle1/pose", "--field", "linear_velocity"]
    seen = NodeProcess(lab, tmp_path / "echo", command=echo)
    twist = "{linear: {x: 2.0, y: 0.0, z: 0.0}, angular: {x: 0.0, y: 0.0, z: -1.8}}"  # the page's command
    pub = [*cli, "topic", "pub", "-r", "1", "/turtlesim1/turtle1/cmd_vel", "geometry_msgs/msg/Twist", twist]
    teleop = NodeProcess(lab, tmp_path / "pub", command=pub)
    try:
        seen.wait_for(r"^2\.0$")  # turtle2 goes at turtle1's speed, which only turtle1 was told
    finally:
        teleop.kill()
        seen.kill()
    launched.stop()


@pytest.mark.parametrize("kind", ["xml", "py", "yaml"])
def test_integrating_launch_files_starts_the_cpp_talker(
    lab: App, launch: type[NodeProcess], kind: str
) -> None:
    launched = launch("py_launch_example", f"my_script_launch.{kind}")
    launched.wait_for(rf"^\[talker-\d+\] \[INFO\] {STAMP} \[talker\]: Publishing: 'Hello World: 1'$")
    assert "/talker" in graph(lab, "node") and "/chatter" in graph(lab, "topic")
    launched.stop()
    assert "/talker" not in graph(lab, "node")


def test_parameters_launch_file_sets_my_parameter_to_earth(lab: App, launch: type[NodeProcess]) -> None:
    launched = launch("python_parameters", "python_parameters_launch.py")
    launched.wait_for(
        rf"^\[minimal_param_node-\d+\] \[INFO\] {STAMP} \[custom_minimal_param_node\]: Hello earth!$"
    )
    launched.wait_for(
        rf"^\[minimal_param_node-\d+\] \[INFO\] {STAMP} \[custom_minimal_param_node\]: Hello world!$"
    )
    assert "/custom_minimal_param_node" in graph(lab, "node")
    launched.stop()


@pytest.mark.parametrize(
    ("file", "arguments", "namespace"),
    [
        ("example_main_launch.py", (), "/turtlesim2"),
        (
            "example_substitutions_launch.py",
            ("turtlesim_ns:=turtlesim3", "use_provided_red:=True", "new_background_r:=200"),
            "/turtlesim3",
        ),
        ("example_substitutions_launch.py", (), "/turtlesim1"),
    ],
)
def test_substitutions_put_turtlesim_in_the_namespace_given(
    lab: App, launch: type[NodeProcess], file: str, arguments: tuple[str, ...], namespace: str
) -> None:
    launched = launch("launch_tutorial", file, *arguments)
    launched.wait_for(
        rf"^\[turtlesim_node-\d+\] \[INFO\] {STAMP} \[[\w./]+\]: Starting turtlesim with node name "
        rf"{namespace}/sim$"
    )
    topics = graph(lab, "topic")
    assert {
        f"{namespace}/turtle1/pose",
        f"{namespace}/turtle1/cmd_vel",
        f"{namespace}/turtle1/color_sensor",
    } <= topics
    assert f"{namespace}/sim" in graph(lab, "node")
    launched.stop()


def param_events(lab: App, tmp_path: Path) -> NodeProcess:
    """``ros2lab topic echo /parameter_events`` (every parameter a node declares or changes), once it
    has shown an event of a node ``/marker`` this publishes until then."""
    cli = cli_command("--url", lab.url)
    events = NodeProcess(lab, tmp_path / "events", command=[*cli, "topic", "echo", "/parameter_events"])
    marker = [
        *cli,
        "topic",
        "pub",
        "-r",
        "5",
        "/parameter_events",
        "rcl_interfaces/msg/ParameterEvent",
        "{node: /marker}",
    ]
    pub = NodeProcess(lab, tmp_path / "marker", command=marker)
    try:
        events.wait_for(r"^node: /marker$")
    finally:
        pub.kill()
    return events


@pytest.mark.parametrize(("kind", "namespace"), [("py", "turtlesim5"), ("yaml", "turtlesim6")])
def test_substitutions_commands_spawn_turtle2_and_set_the_background_to_120_then_200(
    lab: App, launch: type[NodeProcess], tmp_path: Path, kind: str, namespace: str
) -> None:
    """In a namespace of its own: the lab's turtlesim keeps a namespace's turtles, and another test
    spawns there."""
    events = param_events(lab, tmp_path)
    try:
        launched = launch(
            "launch_tutorial",
            f"example_substitutions_launch.{kind}",
            f"turtlesim_ns:={namespace}",
            "use_provided_red:=True",
            "new_background_r:=200",
        )
        # The page: turtle2 spawned by ``ros2 service call``, the background's red at 120 at once
        # by ``ros2 param set``, then at 200 after the TimerAction's two seconds.
        launched.wait_for(r"^\[ros2-\d+\] turtlesim\.srv\.Spawn_Response\(name='turtle2'\)$")
        launched.wait_for(r"^\[ros2-\d+\] Set parameter successful$", count=2)
        events.wait_for(r"name: background_r\n(.*\n){0,3}.*integer_value: 200$")
        first, second = events.wait_for(r"^ *integer_value: (120|200)$", count=2)
        assert (first.group(1), second.group(1)) == ("120", "200")
    finally:
        events.kill()
    assert f"/{namespace}/turtle2/pose" in graph(lab, "topic")
    code, out, err = ros2lab("--url", lab.url, "param", "get", f"/{namespace}/sim", "background_r")
    assert (code, out.strip()) == (0, "Integer value is: 200"), err
    launched.stop()


def test_substitutions_without_use_provided_red_set_the_background_to_120(
    lab: App, launch: type[NodeProcess]
) -> None:
    launched = launch("launch_tutorial", "example_substitutions_launch.py")
    launched.wait_for(r"^\[ros2-\d+\] Set parameter successful$")
    code, out, err = ros2lab("--url", lab.url, "param", "get", "/turtlesim1/sim", "background_r")
    assert (code, out.strip()) == (0, "Integer value is: 120"), err
    launched.stop()


def test_a_launch_files_command_other_than_ros2_is_refused_and_a_ros2_one_ends_with_the_launch(
    lab: App, ws: Path, launch: type[NodeProcess]
) -> None:
    path = ws / "launch" / "touch_launch.py"
    path.write_text(TOUCH_LAUNCH.replace("TOUCHED", str(ws / "touched")))
    launched = launch(str(path))
    launched.wait_for(
        rf"^\[ERROR\] \[launch\]: {path}:6: not run: 'touch {ws}/touched': the lab runs only ros2 "
        r"commands from a launch file \(as its ros2lab CLI\)$"
    )
    launched.wait_for(r"process started: /talker")
    assert not (ws / "touched").exists()
    wait_until(lambda: echoes(ECHOED), f"the launch's ros2 topic echo {ECHOED} to run")
    launched.stop()
    wait_until(lambda: not echoes(ECHOED), f"the launch's ros2 topic echo {ECHOED} to end with it")


def echoes(topic: str) -> list[int]:
    """The processes of this machine whose command line ends with ``topic echo TOPIC``."""
    found = []
    for entry in Path("/proc").iterdir():
        try:
            argv = (entry / "cmdline").read_bytes().split(b"\0")
        except OSError:
            continue  # not a process, or gone meanwhile
        if argv[-3:] == [b"echo", topic.encode(), b""]:
            found.append(int(entry.name))
    return found


ECHOED = "/touch_launch_echo"
TOUCH_LAUNCH = """\
from launch import LaunchDescription
from launch.actions import ExecuteProcess
from launch_ros.actions import Node

def generate_launch_description():
    return LaunchDescription([ExecuteProcess(cmd=['touch', 'TOUCHED']),
                              Node(package='demo_nodes_cpp', executable='talker'),
                              ExecuteProcess(cmd=['ros2', 'topic', 'echo', '/touch_launch_echo'])])
"""
