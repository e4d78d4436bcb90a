"""Parameters the ROS way, across processes: ROS 2's "Using parameters in a class" tutorial in
our own version, started with ``ros2lab run``; ``ros2lab param`` and another node's
AsyncParameterClient reaching a node's callback; refusals with their reasons; ``param dump``
loading back with ``param load`` and ``--params-file``."""

from __future__ import annotations

import contextlib
import io
import signal
import subprocess
from collections.abc import Iterator
from pathlib import Path

import pytest
from support.app import REPO, App
from support.forked_cli import cli_command
from support.wait import wait_until

from server.cli import main as cli_main

from .conftest import make_workspace, node_entry
from .node_process import NodeProcess

STAMP = r"\[\d+\.\d{9}\]"
START_S = 60.0

# ROS 2's tutorial, as Kilted's docs write it: a parameter read on a timer, then set back to world.
MINIMAL_PARAM = """
import rclpy
import rclpy.node
from rcl_interfaces.msg import ParameterDescriptor


class MinimalParam(rclpy.node.Node):
    def __init__(self):
        super().__init__('minimal_param_node')
        descriptor = ParameterDescriptor(description='This parameter is mine!')
        self.declare_parameter('my_parameter', 'world', descriptor)
        self.timer = self.create_timer(0.5, self.timer_callback)

    def timer_callback(self):
        my_param = self.get_parameter('my_parameter').get_parameter_value().string_value
        self.get_logger().info('Hello %s!' % my_param)
        my_new_param = rclpy.parameter.Parameter('my_parameter', rclpy.Parameter.Type.STRING, 'world')
        self.set_parameters([my_new_param])


def main():
    rclpy.init()
    node = MinimalParam()
    try:
        rclpy.spin(node)
    except KeyboardInterrupt:
        pass
    finally:
        rclpy.try_shutdown()


if __name__ == '__main__':
    main()
"""

# A node that guards its parameters: a range, a read-only name, and a callback with its reason.
GUARDED = """
import rclpy
from rclpy.node import Node
from rcl_interfaces.msg import FloatingPointRange, ParameterDescriptor, SetParametersResult


class Guarded(Node):
    def __init__(self):
        super().__init__('guarded_node')
        speed_range = FloatingPointRange(from_value=0.0, to_value=10.0, step=0.0)
        self.declare_parameter('speed', 1.0, ParameterDescriptor(floating_point_range=[speed_range]))
        self.declare_parameter('robot_name', 'rover', ParameterDescriptor(read_only=True))
        self.declare_parameter('mode', 'auto')
        self.declare_parameter('gains.p', 0.5)
        self.add_on_set_parameters_callback(self.check)

    def check(self, params):
        for p in params:
            if p.name == 'mode' and p.value not in ('auto', 'manual'):
                return SetParametersResult(successful=False, reason='mode must be auto or manual')
        for p in params:
            self.get_logger().info(f'{p.name} is now {p.value}')
        return SetParametersResult(successful=True)


def main():
    rclpy.init()
    try:
        rclpy.spin(Guarded())
    except KeyboardInterrupt:
        pass
    finally:
        rclpy.try_shutdown()
"""

# Another process's node, setting guarded_node's parameters through its services.
SETTER = """
import rclpy
from rclpy.parameter import Parameter
from rclpy.parameter_client import AsyncParameterClient

rclpy.init()
node = rclpy.create_node('setter')
client = AsyncParameterClient(node, 'guarded_node')
print('ready:', client.wait_for_services(timeout_sec=10.0), flush=True)
future = client.set_parameters([Parameter('mode', value='manual'), Parameter('mode', value='warp')])
rclpy.spin_until_future_complete(node, future, timeout_sec=10.0)
for result in future.result().results:
    print('result:', result.successful, result.reason, flush=True)
rclpy.shutdown()
"""


@pytest.fixture(scope="module")
def lab(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[App, Path]]:
    root = tmp_path_factory.mktemp("params")
    make_workspace(
        root, {"src/param_lab/minimal_param.py": MINIMAL_PARAM, "src/param_lab/guarded.py": GUARDED}
    )
    app = App(
        root,
        "--launch",
        str(REPO / "server/packages/rocketship/launch/rocket.launch"),
        "start_delay:=600",
        cwd=root,
    )
    try:
        yield app, root
    finally:
        app.stop()


@pytest.fixture
def run(lab: tuple[App, Path]) -> Iterator[type[NodeProcess]]:
    """``ros2lab run param_lab EXE ARGS`` in the lab's folder; each is stopped with Ctrl-C after."""
    app, root = lab
    started: list[NodeProcess] = []

    class Started(NodeProcess):
        def __init__(self, exe: str, *args: str) -> None:
            command = cli_command("--url", app.url, "run", "param_lab", exe, *args)
            super().__init__(app, root / exe, command=command)
            started.append(self)

    yield Started
    for proc in started:
        proc.interrupt()
    app.wait_for(
        lambda: all(node_entry(app, n) is None for n in ("/minimal_param_node", "/guarded_node")),
        "the parameter nodes to leave the graph",
    )


def ros2lab(app: App, cwd: Path, *args: str) -> subprocess.CompletedProcess[str]:
    """The CLI as a user runs it, in a process of its own."""
    return subprocess.run(
        cli_command("--url", app.url, *args),
        cwd=cwd,
        text=True,
        capture_output=True,
        timeout=60,
        check=False,
    )


def param(app: App, *args: str) -> subprocess.CompletedProcess[str]:
    """``ros2lab param ...`` in this process (the same code, without an interpreter's start)."""
    out, err = io.StringIO(), io.StringIO()
    sigterm = signal.getsignal(signal.SIGTERM)  # the CLI takes SIGTERM over, as a command may
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = cli_main(["--url", app.url, "param", *args])
    finally:
        signal.signal(signal.SIGTERM, sigterm)
    return subprocess.CompletedProcess(args, code, out.getvalue(), err.getvalue())


def served(app: App, proc: NodeProcess, node: str) -> None:
    """Until ``node`` answers a call of its parameter services through the lab (a graph that lists
    them could still hold the tokens of an earlier process of that name); a process's start (an
    interpreter, rclpy, a Zenoh session) is given a minute on a busy machine."""
    body = {"request": {}, "type": "rcl_interfaces/srv/ListParameters", "timeout_s": 2.0}
    wait_until(
        lambda: (
            node_entry(app, node) is not None
            and app.post(f"/api/services{node}/list_parameters", body).status_code == 200
        ),
        f"{node} and its parameter services",
        START_S,
        poll_s=0.1,
        detail=lambda: proc.text[-3000:],
    )


def test_the_tutorial_prints_hello_and_takes_param_set_from_ros2lab(
    run: type[NodeProcess], lab: tuple[App, Path]
) -> None:
    app, root = lab
    node = run("minimal_param.py")
    node.wait_for(rf"^\[INFO\] {STAMP} \[minimal_param_node\]: Hello world!$", timeout_s=START_S)
    served(app, node, "/minimal_param_node")
    done = ros2lab(app, root, "param", "set", "/minimal_param_node", "my_parameter", "earth")
    assert (done.returncode, done.stdout, done.stderr) == (0, "Set parameter successful\n", "")
    node.wait_for(rf"^\[INFO\] {STAMP} \[minimal_param_node\]: Hello earth!$")
    node.wait_for(r"Hello earth!\n(.*\n)*.*Hello world!$")  # the node set it back, as the tutorial's does
    listed = param(app, "list", "/minimal_param_node")
    assert listed.stdout == "  my_parameter\n  start_type_description_service\n  use_sim_time\n"
    every = param(app, "list", "--param-type")  # every node process, each under its name
    assert (
        "/minimal_param_node:\n  my_parameter (type: string)\n  start_type_description_service (type: boolean)\n"
        "  use_sim_time (type: boolean)\n" in every.stdout
    )
    described = param(app, "describe", "/minimal_param_node", "my_parameter")
    assert described.stdout == (
        "Parameter name: my_parameter\n  Type: string\n  Description: This parameter is mine!\n  Constraints:\n"
    )
    got = param(app, "get", "/minimal_param_node", "use_sim_time")
    assert got.stdout == "Boolean value is: False\n"


def test_the_tutorial_takes_its_value_from_ros_args(run: type[NodeProcess], tmp_path: Path) -> None:
    params = tmp_path / "params.yaml"
    params.write_text("/**:\n  ros__parameters:\n    my_parameter: mars\n")
    node = run("minimal_param.py", "--ros-args", "--params-file", str(params))
    node.wait_for(rf"^\[INFO\] {STAMP} \[minimal_param_node\]: Hello mars!$", timeout_s=START_S)


def test_refusals_come_back_with_their_reasons(run: type[NodeProcess], lab: tuple[App, Path]) -> None:
    app, _root = lab
    node = run("guarded.py")
    served(app, node, "/guarded_node")
    cases = [
        ("mode", "warp", "Setting parameter failed: mode must be auto or manual\n"),
        ("robot_name", "x", "Setting parameter failed: Trying to set a read-only parameter: robot_name.\n"),
        (
            "speed",
            "11.0",
            "Setting parameter failed: Parameter speed out of range Min: 0.0, Max: 10.0, value: 11.0\n",
        ),
        ("speed", "fast", "Setting parameter failed: Wrong parameter type, expected '3' got '4'\n"),
        ("speed", "5", "Setting parameter failed: Wrong parameter type, expected '3' got '2'\n"),
    ]
    for name, value, err in cases:
        done = param(app, "set", "/guarded_node", name, value)
        assert (done.returncode, done.stdout, done.stderr) == (0, "", err)
    done = param(app, "set", "/guarded_node", "speed", "2.5")  # what is allowed still is
    assert done.stdout == "Set parameter successful\n"
    node.wait_for(rf"^\[INFO\] {STAMP} \[guarded_node\]: speed is now 2.5$")
    got = param(app, "get", "/guarded_node", "speed")
    assert got.stdout == "Double value is: 2.5\n"
    assert "is now" not in node.text.replace("speed is now 2.5", "")  # no refused value reached the node


def test_another_process_sets_through_async_parameter_client(
    run: type[NodeProcess], lab: tuple[App, Path], tmp_path: Path
) -> None:
    app, _root = lab
    node = run("guarded.py")
    served(app, node, "/guarded_node")
    setter_file = tmp_path / "setter.py"
    setter_file.write_text(SETTER)
    setter = NodeProcess(app, setter_file)
    try:
        assert setter.finish(START_S) == 0, setter.text
    finally:
        setter.kill()
    assert "ready: True" in setter.text
    assert "result: True \nresult: False mode must be auto or manual" in setter.text
    node.wait_for(rf"^\[INFO\] {STAMP} \[guarded_node\]: mode is now manual$")


def test_dump_loads_back_with_param_load_and_params_file(
    run: type[NodeProcess], lab: tuple[App, Path], tmp_path: Path
) -> None:
    app, _root = lab
    node = run("guarded.py")
    served(app, node, "/guarded_node")
    for name, value in (("speed", "7.5"), ("mode", "manual"), ("gains.p", "0.25")):
        assert param(app, "set", "/guarded_node", name, value).returncode == 0
    dumped = param(app, "dump", "/guarded_node")
    assert dumped.stdout == (
        "/guarded_node:\n  ros__parameters:\n    gains:\n      p: 0.25\n    mode: manual\n"
        "    robot_name: rover\n    speed: 7.5\n    start_type_description_service: true\n"
        "    use_sim_time: false\n\n"
    )
    saved = tmp_path / "guarded.yaml"
    saved.write_text(dumped.stdout.replace("speed: 7.5", "speed: 3.0"))
    node.interrupt()
    app.wait_for(lambda: node_entry(app, "/guarded_node") is None, "the first guarded_node to leave")
    fresh = run("guarded.py", "--ros-args", "--params-file", str(saved))
    served(app, fresh, "/guarded_node")
    got = param(app, "get", "/guarded_node", "speed")
    assert got.stdout == "Double value is: 3.0\n"  # from the file, at declaration
    assert param(app, "set", "/guarded_node", "speed", "1.0").returncode == 0
    loaded = param(app, "load", "/guarded_node", str(saved))
    assert loaded.stdout.splitlines() == [
        "Set parameter gains.p successful",
        "Set parameter mode successful",
        "Set parameter speed successful",
        "Set parameter use_sim_time successful",
    ]
    assert loaded.stderr == (
        "Set parameter robot_name failed: Trying to set a read-only parameter: robot_name.\n"
        "Set parameter start_type_description_service failed: Trying to set a read-only parameter: "
        "start_type_description_service.\n"
    )
    fresh.wait_for(rf"^\[INFO\] {STAMP} \[guarded_node\]: speed is now 3.0$")
    assert param(app, "get", "/guarded_node", "speed").stdout == "Double value is: 3.0\n"


def test_a_params_file_that_does_not_parse_is_one_line_and_changes_nothing(
    run: type[NodeProcess], lab: tuple[App, Path], tmp_path: Path
) -> None:
    app, _root = lab
    bad = tmp_path / "bad.yaml"
    bad.write_text("guarded_node:\n  ros__parameters:\n    speed: [1.0\n")
    refused = run("guarded.py", "--ros-args", "--params-file", str(bad))
    assert refused.finish(START_S) == 2
    assert refused.text == f"{bad}:4: not valid YAML: expected ',' or ']', but got '<stream end>'", (
        refused.text
    )
    node = run("guarded.py")
    served(app, node, "/guarded_node")
    loaded = param(app, "load", "/guarded_node", str(bad))
    assert (loaded.returncode, loaded.stdout) == (1, "")
    assert loaded.stderr.count("\n") == 1 and loaded.stderr.startswith(f"{bad}:4: not valid YAML")
    assert param(app, "get", "/guarded_node", "speed").stdout == "Double value is: 1.0\n"
    assert "is now" not in node.text
    assert app.get("/api/health") is not None  # the lab goes on


def test_the_labs_own_nodes_answer_ros2lab_param(lab: tuple[App, Path]) -> None:
    """The launch's nodes run inside the app: they serve the same services as a node process."""
    app, _root = lab
    assert param(app, "list", "/CountDownNode").stdout == "  start_delay_s\n  use_sim_time\n"  # as rclpy's
    assert (
        "/keyboard:\n  allow_repeat (type: boolean)\n  use_sim_time (type: boolean)\n"
        in param(app, "list", "--param-type").stdout
    )
    assert param(app, "get", "/keyboard", "use_sim_time").stdout == "Boolean value is: False\n"
    assert param(app, "get", "/CountDownNode", "start_delay_s").stdout == "Double value is: 600.0\n"
    described = param(app, "describe", "/CountDownNode", "start_delay_s").stdout
    assert "  Type: double\n  Description: seconds before lift-off\n" in described
    assert "    Read only: true\n" in described
    refused = param(app, "set", "/CountDownNode", "start_delay_s", "1.0")
    assert refused.stderr == "Setting parameter failed: Trying to set a read-only parameter: start_delay_s.\n"
    assert param(app, "get", "/CountDownNode", "start_delay_s").stdout == "Double value is: 600.0\n"
    wrong = param(app, "set", "/keyboard", "allow_repeat", "often")
    assert wrong.stderr == "Setting parameter failed: Wrong parameter type, expected '1' got '4'\n"
    try:
        done = param(app, "set", "/keyboard", "allow_repeat", "true")
        assert (done.returncode, done.stdout, done.stderr) == (0, "Set parameter successful\n", "")
        assert param(app, "get", "/keyboard", "allow_repeat").stdout == "Boolean value is: True\n"
        dumped = param(app, "dump", "/keyboard").stdout
        assert dumped == "/keyboard:\n  ros__parameters:\n    allow_repeat: true\n    use_sim_time: false\n\n"
    finally:
        param(app, "set", "/keyboard", "allow_repeat", "false")
    assert param(app, "get", "/keyboard", "allow_repeat").stdout == "Boolean value is: False\n"


# A node process reading and setting the app's own nodes over the Zenoh wire.
IN_APP_CLIENT = """
import rclpy
from rclpy.parameter import Parameter
from rclpy.parameter_client import AsyncParameterClient

rclpy.init()
node = rclpy.create_node('in_app_setter')
countdown = AsyncParameterClient(node, '/CountDownNode')
print('ready:', countdown.wait_for_services(timeout_sec=20.0), flush=True)
future = countdown.get_parameters(['start_delay_s'])
rclpy.spin_until_future_complete(node, future, timeout_sec=10.0)
print('delay:', future.result().values[0].double_value, flush=True)
future = countdown.set_parameters([Parameter('start_delay_s', value=1.0)])
rclpy.spin_until_future_complete(node, future, timeout_sec=10.0)
print('countdown:', future.result().results[0].successful, future.result().results[0].reason, flush=True)
keyboard = AsyncParameterClient(node, '/keyboard')
keyboard.wait_for_services(timeout_sec=20.0)
future = keyboard.set_parameters([Parameter('allow_repeat', value=True)])
rclpy.spin_until_future_complete(node, future, timeout_sec=10.0)
print('keyboard:', future.result().results[0].successful, flush=True)
rclpy.shutdown()
"""


def test_a_node_process_reads_and_sets_the_labs_own_nodes_over_zenoh(
    lab: tuple[App, Path], tmp_path: Path
) -> None:
    app, _root = lab
    script = tmp_path / "in_app_setter.py"
    script.write_text(IN_APP_CLIENT)
    setter = NodeProcess(app, script)
    try:
        try:
            assert setter.finish(START_S) == 0, setter.text
        finally:
            setter.kill()
        assert "ready: True\ndelay: 600.0\n" in setter.text
        assert "countdown: False Trying to set a read-only parameter: start_delay_s." in setter.text
        assert "keyboard: True" in setter.text
        assert param(app, "get", "/keyboard", "allow_repeat").stdout == "Boolean value is: True\n"
    finally:
        param(app, "set", "/keyboard", "allow_repeat", "false")
