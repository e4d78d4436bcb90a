"""A launch file's commands (YAML and XML ``executable``, ``timer``, ``$(eval)``) in the description,
and which of them the launcher runs: ``ros2 ...`` only, and none on a server that serves others."""

from __future__ import annotations

import pytest
from launchfiles import FindShare, Parse, Write, error_of

from node_runtime.bus import Bus
from node_runtime.bus.clock import ManualClock
from server.host.processes.supervisor import Supervisor
from server.services.launch.commands import NOT_HERE, CommandRunner, LabCli
from server.services.launch.description import CommandAction, SourceLocation
from server.services.launch.expressions import evaluate_expression
from server.services.launch.substitutions import SubstitutionError
from server.services.launch.xml_parser import parse_launch_file

# docs.ros.org's "Using substitutions", its YAML launch file as the page writes it.
SUBSTITUTIONS_YAML = """\
launch:
  - arg:
      name: 'turtlesim_ns'
      default: 'turtlesim1'
  - arg:
      name: 'use_provided_red'
      default: 'False'
  - arg:
      name: 'new_background_r'
      default: '200'

  - node:
      pkg: 'turtlesim'
      namespace: '$(var turtlesim_ns)'
      exec: 'turtlesim_node'
      name: 'sim'
  - executable:
      cmd: 'ros2 service call $(var turtlesim_ns)/spawn turtlesim/srv/Spawn "{x: 5, y: 2, theta: 0.2}"'
  - executable:
      cmd: 'ros2 param set $(var turtlesim_ns)/sim background_r 120'
  - timer:
      period: 2.0
      children:
        - executable:
            cmd: 'ros2 param set $(var turtlesim_ns)/sim background_r $(var new_background_r)'
            if: '$(eval "$(var new_background_r) == 200 and $(var use_provided_red)")'
"""


def test_the_yaml_substitutions_tutorial_gives_its_three_commands_the_last_two_seconds_later(
    write: Write, find_share: FindShare
) -> None:
    path = write("example_substitutions_launch.yaml", SUBSTITUTIONS_YAML)

    description = parse_launch_file(
        path, args={"turtlesim_ns": "t3", "use_provided_red": "True"}, find_package_share=find_share
    )

    spawn, red, conditioned = description.commands
    assert spawn.cmd == (
        "ros2",
        "service",
        "call",
        "t3/spawn",
        "turtlesim/srv/Spawn",
        "{x: 5, y: 2, theta: 0.2}",
    )
    assert (spawn.shell, spawn.start_delay_s, spawn.location.line) == (False, 0.0, 17)
    assert (red.cmd[-3:], red.start_delay_s) == (("t3/sim", "background_r", "120"), 0.0)
    assert (conditioned.cmd[-1], conditioned.start_delay_s, conditioned.location.line) == ("200", 2.0, 24)
    assert [n.namespace for n in description.nodes] == ["/t3"]
    unconditioned = parse_launch_file(path, args={}, find_package_share=find_share)
    assert len(unconditioned.commands) == 2  # use_provided_red False: 200 == 200 and False


def test_xml_executable_in_a_timer_delays_its_nodes_and_commands_too(parse: Parse) -> None:
    description = parse("""<launch>
      <timer period="1.5"><group><timer period="0.5">
        <node pkg="demo" exec="talker"/>
        <executable cmd="ros2 topic list" args="-t" name="lister" output="screen" shell="true"/>
      </timer></group></timer>
      <executable cmd="ros2 node list" unless="$(eval '1 &lt; 2')"/>
    </launch>""")

    (node,) = description.nodes
    (command,) = description.commands
    assert node.start_delay_s == command.start_delay_s == 2.0
    assert command == CommandAction(
        ("ros2 topic list -t",), True, "lister", "screen", SourceLocation("/lab/test.launch", 4), 2.0
    )


@pytest.mark.parametrize(
    ("element", "problem"),
    [
        ('<timer period="soon"/>', 'period="soon" is not a number of seconds >= 0'),
        ('<timer period="-1"/>', 'period="-1" is not a number of seconds >= 0'),
        ('<executable cmd=" "/>', "<executable> has an empty cmd="),
        ('<executable cmd="ros2 \'a"/>', "No closing quotation"),
        ('<executable cmd="ros2" output="loud"/>', 'output="loud" is not one of'),
        ('<executable cmd="ros2" shell="maybe"/>', 'shell="maybe" is not a boolean'),
        ('<executable cmd="ros2" cwd="/"/>', "unknown attribute 'cwd' on <executable>"),
        ('<timer><node pkg="a" exec="b"/></timer>', "<timer> needs the attribute 'period'"),
    ],
)
def test_a_bad_executable_or_timer_names_its_line(parse: Parse, element: str, problem: str) -> None:
    error = error_of(parse, f"<launch>\n{element}</launch>")

    assert error.line == 2 and problem in error.problem, error.problem


@pytest.mark.parametrize(
    ("expression", "value"),
    [
        ("200 == 200 and True", "True"),
        ("100 == 200 and True", "False"),
        ("'a' in ('a', 'b')", "True"),
        ("1 + 2 * 3 - 4 / 2", "5.0"),
        ("not 0 or None", "True"),
        ("'x' if 2 > 1 > 0 else 'y'", "x"),
        ("-pi < 0", "True"),
    ],
)
def test_eval_takes_what_launch_files_compute(expression: str, value: str) -> None:
    assert evaluate_expression(expression) == value


@pytest.mark.parametrize(
    ("expression", "problem"),
    [
        ("__import__('os')", "does not take Call"),
        ("open", "knows no name 'open'"),
        ("().__class__", "does not take Attribute"),
        ("9 ** 9 ** 9", "does not take BinOp"),
        ("'a' * 99", "does not repeat strings"),
        ("1 / 0", "ZeroDivisionError"),
        ("1 +", "is not a Python expression"),
    ],
)
def test_eval_refuses_anything_else_with_the_reason(expression: str, problem: str) -> None:
    with pytest.raises(SubstitutionError, match=problem.replace("(", r"\(")):
        evaluate_expression(expression)


def runner(cli: LabCli | None) -> CommandRunner:
    bus = Bus(ManualClock())
    commands = CommandRunner(Supervisor(bus, lambda _process: None), lambda: pytest.fail("no timer here"))
    commands.cli = cli
    return commands


def action(*cmd: str, shell: bool = False) -> CommandAction:
    return CommandAction(cmd, shell, None, None, SourceLocation("/ws/x.launch.py", 7))


def test_a_program_other_than_ros2_is_refused_in_one_line_naming_it() -> None:
    commands = runner(LabCli("http://127.0.0.1:8000"))

    started, refused = commands.start_all((action("ls", "-l"), action("ros2 topic list | sh", shell=True)))

    assert started == [] and commands.running == [] and commands.supervisor.processes == []
    assert refused == [
        "[ERROR] [launch]: /ws/x.launch.py:7: not run: 'ls -l': the lab runs only ros2 commands from a launch "
        "file (as its ros2lab CLI)",
        "[ERROR] [launch]: /ws/x.launch.py:7: not run: 'ros2 topic list | sh' is more than one command "
        "(it has '|')",
    ]


def test_on_a_server_that_serves_others_no_command_runs() -> None:
    commands = runner(None)

    started, refused = commands.start_all((action("ros2", "param", "set", "/sim", "background_r", "120"),))

    assert started == [] and commands.supervisor.processes == []
    assert refused == [
        f"[ERROR] [launch]: /ws/x.launch.py:7: not run: 'ros2 param set /sim background_r 120': {NOT_HERE}"
    ]
