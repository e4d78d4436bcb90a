"""A launch file's ``ros2 ...`` command becomes the lab's CLI; nothing else is run."""

from __future__ import annotations

import sys

import pytest

from server.services.launch.ros2_commands import CommandNotRunError, cli_argv, command_words

URL = "http://127.0.0.1:8123"
CLI = [sys.executable, "-P", "-m", "server", "--url", URL]


def test_a_shell_command_of_the_substitutions_tutorial_splits_as_the_shell_splits_it() -> None:
    cmd = ['ros2 service call turtlesim2/spawn turtlesim/srv/Spawn "{x: 2, y: 2, theta: 0.2}"']
    assert cli_argv(cmd, shell=True, url=URL) == [
        *CLI,
        "service",
        "call",
        "turtlesim2/spawn",
        "turtlesim/srv/Spawn",
        "{x: 2, y: 2, theta: 0.2}",
    ]


def test_parts_are_joined_with_spaces_for_a_shell_and_kept_as_they_are_without_one() -> None:
    assert command_words(["ros2 param set", "turtlesim2/sim background_r", "120"], shell=True) == [
        "ros2",
        "param",
        "set",
        "turtlesim2/sim",
        "background_r",
        "120",
    ]
    assert cli_argv(
        ["/opt/ros/kilted/bin/ros2", "param", "set", "/sim", "background_r", "a b"], shell=False, url=URL
    ) == [*CLI, "param", "set", "/sim", "background_r", "a b"]


@pytest.mark.parametrize(
    ("cmd", "shell", "why"),
    [
        (["rm", "-rf", "/"], False, "the lab runs only ros2 commands"),
        (["ros2 topic list; rm -rf ~"], True, "more than one command (it has ';')"),
        (["ros2 topic list && ls"], True, "more than one command (it has '&&')"),
        (["ros2 topic list > out.txt"], True, "more than one command (it has '>')"),
        (["ros2 param set /sim background_r $(cat x)"], True, "command substitution"),
        (['ros2 service call "/spawn'], True, "does not parse as a shell command"),
        ([], False, "the command is empty"),
    ],
)
def test_anything_else_is_not_run_and_says_why(cmd: list[str], shell: bool, why: str) -> None:
    with pytest.raises(CommandNotRunError, match=r"^not run: ") as caught:
        cli_argv(cmd, shell=shell, url=URL)
    assert why in str(caught.value)
