"""What a launch file's command (``ExecuteProcess``, ``<executable>``) runs here: ``ros2 ...``, as
the lab's own CLI against this lab.

ROS 2's tutorials run ``ros2 service call`` and ``ros2 param set`` from launch files. The lab has
no ``ros2`` on its PATH; its CLI (``python -m server``, ``ros2lab``) takes the same verbs, so a
command whose program is ``ros2`` runs as that, told the lab's URL. Nothing else runs: a launch
file is a student's, and the server runs no program of theirs outside a node's sandbox. A shell
command (``shell=True``) is split as the shell would split it, and refused if it asks the shell
for more than one plain command (``;``, ``&&``, ``|``, a redirection, a substitution).
"""

from __future__ import annotations

import shlex
import sys
from collections.abc import Sequence
from pathlib import PurePath

PROGRAM = "ros2"
SHELL_PUNCTUATION = frozenset(";&|<>()")
CLI = [sys.executable, "-P", "-m", "server"]  # -P: a folder named server where it starts is not ours


class CommandNotRunError(ValueError):
    """A launch file's command the lab does not run; the message says which and why."""


def command_words(cmd: Sequence[str], *, shell: bool) -> list[str]:
    """The program and its arguments: ``cmd`` itself, or with ``shell`` its parts joined by spaces
    and split as a shell splits them (CommandNotRunError for anything but one plain command)."""
    if not shell:
        return list(cmd)
    line = " ".join(cmd)
    if "$(" in line or "`" in line:
        raise CommandNotRunError(f"not run: {line!r} asks the shell for a command substitution")
    lexer = shlex.shlex(line, posix=True, punctuation_chars=True)
    lexer.whitespace_split = True
    try:
        words = list(lexer)
    except ValueError as exc:  # an unclosed quote
        raise CommandNotRunError(f"not run: {line!r} does not parse as a shell command ({exc})") from None
    operator = next((w for w in words if w and set(w) <= SHELL_PUNCTUATION), None)
    if operator is not None:
        raise CommandNotRunError(f"not run: {line!r} is more than one command (it has {operator!r})")
    return words


def cli_argv(cmd: Sequence[str], *, shell: bool, url: str) -> list[str]:
    """The lab's CLI for ``ros2 VERB ...`` against the lab at ``url``; CommandNotRunError for any
    other program."""
    words = command_words(cmd, shell=shell)
    if not words:
        raise CommandNotRunError("not run: the command is empty")
    if PurePath(words[0]).name != PROGRAM:
        raise CommandNotRunError(
            f"not run: {shlex.join(words)!r}: the lab runs only ros2 commands from a launch file "
            "(as its ros2lab CLI)"
        )
    return [*CLI, "--url", url, *words[1:]]
