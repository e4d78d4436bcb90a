"""An XML or YAML launch file's ``executable`` (a command) and ``timer`` (its actions later), as the
evaluator reads them: ``cmd`` (and ``args``) split into words as a shell splits them, ``name``,
``output``, ``shell``; a timer's ``period`` in seconds, added to what its nodes and commands wait.
Which commands run is the launcher's business (server/services/launch/commands.py).
"""

from __future__ import annotations

import dataclasses
import shlex
from typing import TYPE_CHECKING

from server.services.launch.description import CommandAction, SourceLocation
from server.services.launch.values import OUTPUTS, parse_bool

if TYPE_CHECKING:
    from server.services.launch.evaluation import FileEvaluator, _Frame
    from server.services.launch.xml_tree import Element


def command(evaluator: FileEvaluator, element: Element, frame: _Frame) -> CommandAction:
    """The ``executable`` element as a command to run, every substitution performed."""
    text = " ".join(
        filter(None, (evaluator._sub(element, "cmd", frame), evaluator._optional(element, "args", frame)))
    )
    try:
        words = tuple(shlex.split(text))
    except ValueError as err:
        raise evaluator._error(element, f'cmd="{text}": {err}') from None
    if not words:
        raise evaluator._error(element, "<executable> has an empty cmd=")
    shell_text = evaluator._optional(element, "shell", frame)
    shell = False if shell_text is None else parse_bool(shell_text)
    if shell is None:
        raise evaluator._error(element, f'shell="{shell_text}" is not a boolean: use true or false')
    output = evaluator._optional(element, "output", frame)
    if output is not None and output not in OUTPUTS:
        raise evaluator._error(element, f'output="{output}" is not one of {", ".join(OUTPUTS)}')
    return CommandAction(
        # With shell, the shell's own words (;, &&, |) stay for the launcher to refuse.
        cmd=(text,) if shell else words,
        shell=shell,
        name=evaluator._optional(element, "name", frame),
        output=output,
        location=SourceLocation(evaluator.file, element.line),
        start_delay_s=frame.delay_s,
    )


def timer_frame(evaluator: FileEvaluator, element: Element, frame: _Frame) -> _Frame:
    """What a ``timer``'s actions see: its frame, with ``period`` seconds more to wait."""
    text = evaluator._sub(element, "period", frame)
    try:
        period_s = float(text)
    except ValueError:
        period_s = -1.0
    if not 0.0 <= period_s < float("inf"):
        raise evaluator._error(element, f'period="{text}" is not a number of seconds >= 0')
    return dataclasses.replace(frame, delay_s=frame.delay_s + period_s)
