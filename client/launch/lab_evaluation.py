"""The lab's evaluation of a Python launch file, in a process of its own (the node runner's
``--launch-description FILE REQUEST``; on a class server inside the students' sandbox).

``REQUEST`` is JSON: ``{"args": {name: value}, "namespace": ns or null}``. What is printed on
stdout is one JSON object: ``{"found": [...], "args": {...}, "files": [...], "messages": [...]}``
(nodes and XML/YAML includes in launch order, the top file's declared arguments, the Python files
read, LogInfo's lines and what was not run, every argument name the Python files declare), or ``{"error": "FILE:LINE: problem"}``. What the
launch file prints goes to stderr.
"""

from __future__ import annotations

import contextlib
import difflib
import json
import sys
import traceback
from typing import Any

from launch.action import Action
from launch.launch_context import LaunchContext
from launch.launch_description_entity import LaunchDescriptionEntity
from launch.launch_description_sources.launch_description_source import include_python

MAX_ENTITIES = 100_000  # a generator of actions that never ends stops here


class LaunchProblem(Exception):
    def __init__(self, where: tuple[str, int] | None, problem: str) -> None:
        super().__init__(problem)
        self.where = where


def evaluate(path: str, args: dict[str, str], namespace: str | None) -> dict[str, Any]:
    """What the launch file at ``path`` starts with ``args`` given; LaunchProblem if it cannot."""
    context = LaunchContext()
    context.launch_configurations.update(args)
    if namespace:
        context.launch_configurations["ros_namespace"] = namespace
    context.files.append(path)
    pending: list[LaunchDescriptionEntity] = []
    entity: LaunchDescriptionEntity | None = None
    try:
        pending = list(include_python(context, path))
        for visited in range(MAX_ENTITIES + 1):
            if not pending:
                break
            if visited == MAX_ENTITIES:
                raise LaunchProblem(None, f"more than {MAX_ENTITIES} actions in one launch")
            entity = pending.pop(0)
            pending[:0] = entity.visit(context) or []
    except LaunchProblem:
        raise
    except SyntaxError as exc:
        raise LaunchProblem((exc.filename or path, exc.lineno or 0), f"SyntaxError: {exc.msg}") from None
    except SystemExit as exc:
        raise LaunchProblem(None, f"the launch file called sys.exit({exc.code!r})") from None
    except Exception as exc:
        raise _located(exc, entity, context) from None
    if not any(entry["kind"] == "include" for entry in context.found):
        _check_args(args, context)  # else the launcher checks them, with the included files' own
    declared = sorted({name for names in context.declared.values() for name in names})
    return {
        "found": context.found,
        "args": context.declared.get(path, {}),
        "files": context.files,
        "messages": context.messages,
        "declared": declared,
    }


def _check_args(args: dict[str, str], context: LaunchContext) -> None:
    declared = {name for names in context.declared.values() for name in names}
    for name in args:
        if name not in declared:
            close = difflib.get_close_matches(name, sorted(declared), n=1)
            hint = f"; did you mean '{close[0]}'?" if close else ""
            raise LaunchProblem(
                None, f"argument '{name}' was given but the launch declares no such argument{hint}"
            )


def _located(exc: Exception, entity: LaunchDescriptionEntity | None, context: LaunchContext) -> LaunchProblem:
    """The problem at the launch file's line: the deepest frame in one of its files (code of the
    student's that raised), else where the action that failed was written."""
    frames = [f for f in traceback.extract_tb(exc.__traceback__) if f.filename in context.files]
    if frames:
        where: tuple[str, int] | None = (frames[-1].filename, frames[-1].lineno or 0)
    else:
        where = entity.written_at if isinstance(entity, Action) else None
    message = str(exc) if _ours(exc) else f"{type(exc).__name__}: {exc}"
    return LaunchProblem(where, message)


def _ours(exc: Exception) -> bool:
    """An exception whose message says it all (the launch packages' own), not a bug's."""
    from launch.conditions import InvalidConditionExpressionError
    from launch.launch_description_sources import InvalidPythonLaunchFileError
    from launch.substitutions import SubstitutionFailure

    ours = (InvalidConditionExpressionError, InvalidPythonLaunchFileError, SubstitutionFailure)
    return isinstance(exc, ours) or type(exc) is RuntimeError


def problem_line(path: str, exc: Exception) -> str:
    if isinstance(exc, LaunchProblem):
        file, line = exc.where or (path, 0)
        return f"{file}:{line}: {exc}"
    return f"{path}:0: {type(exc).__name__}: {exc}"


def main(path: str, request: str) -> int:
    """Evaluate and print the result as JSON on the real stdout; the launch file's own prints go
    to stderr."""
    out = sys.stdout
    try:
        asked = json.loads(request)
        args = {str(k): str(v) for k, v in dict(asked.get("args") or {}).items()}
        with contextlib.redirect_stdout(sys.stderr):
            result = evaluate(path, args, asked.get("namespace"))
        text = json.dumps(result)
    except Exception as exc:
        text = json.dumps({"error": problem_line(path, exc)})
    out.write(text + "\n")
    out.flush()
    return 0
