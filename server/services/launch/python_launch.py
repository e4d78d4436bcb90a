"""Python launch files (``.launch.py``) in the one launch model: what the file's process answered
(server/services/launch/python_process.py) becomes the nodes and commands XML would give, and the XML or YAML files it
includes are read by the same evaluator as a file launched alone, in the namespace pushed where
they are included. Includes between Python files happen inside the process, as in ROS 2.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any, cast

from node_runtime.params_file import ParamsFile
from server.services.launch.description import (
    CommandAction,
    LaunchDescription,
    LaunchFileError,
    NodeAction,
    ParamValue,
    SourceLocation,
)
from server.services.launch.evaluation import (
    FileEvaluator,
    FindPackageShare,
    IncludePython,
    Session,
    load_include,
    read_param_file,
)
from server.services.launch.python_process import Evaluation
from server.services.launch.values import OUTPUTS
from server.services.launch.xml_tree import declared_names, did_you_mean

MAX_MESSAGES = 200  # lines shown with a launch (every GET /api/launches repeats them)
MAX_MESSAGE_CHARS = 2000
RunPython = Callable[[Path, Mapping[str, str], "str | None"], Evaluation]
"""Evaluates one Python launch file in its process: its path, the arguments, the namespace pushed."""


def evaluate_python_file(
    path: Path,
    args: Mapping[str, str],
    find_package_share: FindPackageShare,
    run: RunPython,
    environ: Mapping[str, str] | None = None,
    roots: tuple[Path, ...] | None = None,
) -> LaunchDescription:
    """A Python launch file and everything it includes, as one flat description."""
    file = str(path)
    if not path.is_file():
        raise LaunchFileError(file, 0, "launch file not found")
    session = Session(
        find_package_share, os.environ if environ is None else environ, roots, include_python_with(run)
    )
    session.note_file(file)
    evaluation = run(path, args, None)
    included_args: set[str] = set()
    declared = _absorb(session, path, evaluation, (path.resolve(),), run, included_args)
    known = {*_strings(evaluation.answer.get("declared")), *included_args}
    for name in args:
        if name not in known:
            raise LaunchFileError(
                file,
                0,
                f"argument '{name}' was given but the launch declares no such "
                f"argument{did_you_mean(name, known)}",
            )
    return session.description(declared)


def include_python_with(run: RunPython) -> IncludePython:
    """``Session.include_python`` for files that include a Python one, evaluated by ``run``."""

    def include(
        session: Session, path: Path, args: Mapping[str, str], namespace: str | None, stack: tuple[Path, ...]
    ) -> None:
        _absorb(session, path, run(path, args, namespace), stack, run)

    return include


def _absorb(
    session: Session,
    path: Path,
    evaluation: Evaluation,
    stack: tuple[Path, ...],
    run: RunPython,
    included_args: set[str] | None = None,
) -> dict[str, str]:
    """The evaluation of ``path``: its nodes and includes into ``session``; its arguments. The names
    the XML and YAML files it includes declare are added to ``included_args``. The answer came from
    a student's code: one that is not what the evaluation writes is refused, not trusted."""
    try:
        return _absorb_answer(session, evaluation, stack, run, included_args)
    except (ValueError, TypeError, AttributeError, OverflowError):
        raise LaunchFileError(str(path), 0, "its evaluation did not answer a launch description") from None


def _absorb_answer(
    session: Session,
    evaluation: Evaluation,
    stack: tuple[Path, ...],
    run: RunPython,
    included_args: set[str] | None,
) -> dict[str, str]:
    answer = evaluation.answer
    for file in _strings(answer.get("files")):
        session.note_file(file)
    for line in [*_strings(answer.get("messages")), *evaluation.printed]:
        if len(session.messages) < MAX_MESSAGES:
            session.messages.append(line[:MAX_MESSAGE_CHARS])
    for entry in _entries(answer.get("found")):
        if entry.get("kind") == "node":
            session.nodes.append(_node(session, entry))
        elif entry.get("kind") == "command":
            session.commands.append(_command(entry))
        elif entry.get("kind") == "include":
            declared_there = _include(session, entry, stack, run)
            if included_args is not None:
                included_args |= declared_there
    declared = answer.get("args")
    return {str(k): str(v) for k, v in declared.items()} if isinstance(declared, dict) else {}


def _include(session: Session, entry: Mapping[str, Any], stack: tuple[Path, ...], run: RunPython) -> set[str]:
    at_entry = entry.get("at")
    if not isinstance(at_entry, dict):
        at_entry = {}
    at = (str(at_entry.get("file", "")), int(at_entry.get("line", 0)))
    path = Path(str(entry.get("file")))
    if not path.is_absolute():
        path = Path(at[0]).parent / path
    passed = {str(k): str(v) for k, v in dict(entry.get("args") or {}).items()}
    namespace = entry.get("namespace")
    root = load_include(session, stack, path, at)
    declared = declared_names(root)
    for name in passed:
        if name not in declared:
            listed = ", ".join(sorted(declared)) or "none"
            raise LaunchFileError(
                *at,
                f"{path} declares no argument '{name}'{did_you_mean(name, declared)} (it declares: {listed})",
            )
    session.note_file(str(path))
    origin = f"the include at {at[0]}:{at[1]}"
    inherited = entry.get("inherited")
    if isinstance(inherited, dict):  # the includer's launch configurations, for the arguments declared
        passed.update(
            {name: str(inherited[name]) for name in declared if name in inherited and name not in passed}
        )
    FileEvaluator(session, str(path), passed, (*stack, path.resolve()), origin).run(
        root, str(namespace) if namespace else None
    )
    return declared


def _node(session: Session, entry: Mapping[str, Any]) -> NodeAction:
    location = SourceLocation(str(entry.get("file", "")), int(entry.get("line", 0)))

    def fail(problem: str) -> LaunchFileError:
        return LaunchFileError(location.file, location.line, problem)

    pkg, executable = str(entry.get("pkg") or ""), str(entry.get("exec") or "")
    if not pkg or not executable:
        raise fail("Node has an empty package= or executable=")
    output = entry.get("output")
    if output is not None and output not in OUTPUTS:
        raise fail(f"output='{output}' is not one of {', '.join(OUTPUTS)}")
    parameters: list[tuple[str, ParamValue]] = []
    for name, value in _pairs(entry.get("parameters")):
        try:
            parameters.append((name, _param_value(value)))
        except ValueError as err:
            raise fail(f"parameter '{name}': {err}") from None
    files: list[ParamsFile] = [
        read_param_file(session, text, location.file, location.line)
        for text in _strings(entry.get("parameter_files"))
    ]
    remappings = tuple((str(a), str(b)) for a, b in _pairs(entry.get("remappings")))
    return NodeAction(
        pkg=pkg,
        exec=executable,
        name=_optional(entry.get("name")),
        namespace=_optional(entry.get("namespace")),
        output=cast("str | None", output),
        respawn=bool(entry.get("respawn")),
        respawn_delay_s=max(0.0, float(entry.get("respawn_delay") or 0.0)),
        start_delay_s=_seconds(entry.get("start_delay")),
        parameters=tuple(parameters),
        remappings=_first_wins(remappings),
        location=location,
        parameter_files=tuple(files),
        arguments=tuple(_strings(entry.get("arguments"))),
        ros_arguments=tuple(_strings(entry.get("ros_arguments"))),
    )


def _command(entry: Mapping[str, Any]) -> CommandAction:
    location = SourceLocation(str(entry.get("file", "")), int(entry.get("line", 0)))
    output = entry.get("output")
    if output is not None and output not in OUTPUTS:
        raise LaunchFileError(
            location.file,
            location.line,
            f"ExecuteProcess output='{output}' is not one of {', '.join(OUTPUTS)}",
        )
    return CommandAction(
        cmd=tuple(_strings(entry.get("cmd"))),
        shell=bool(entry.get("shell")),
        name=_optional(entry.get("name")),
        output=cast("str | None", output),
        location=location,
        start_delay_s=_seconds(entry.get("start_delay")),
    )


def _first_wins(remappings: tuple[tuple[str, str], ...]) -> tuple[tuple[str, str], ...]:
    """As rcl reads remap rules: the first for a name applies (a group's SetRemap before the node's own)."""
    seen: dict[str, str] = {}
    for source, target in remappings:
        seen.setdefault(source, target)
    return tuple(seen.items())


def _param_value(value: Any) -> ParamValue:
    if isinstance(value, bool | int | float | str):
        return value
    if isinstance(value, list) and all(isinstance(v, bool | int | float | str) for v in value):
        kinds = sorted({type(v).__name__ for v in value})
        if len(kinds) > 1:
            raise ValueError(f"{value} mixes {' and '.join(kinds)}; a ROS parameter list holds one type")
        return cast(ParamValue, value)
    raise ValueError(
        f"{value!r} is not a ROS parameter value (a bool, int, float, str or a list of one of them)"
    )


def _seconds(value: Any) -> float:
    seconds = float(value) if isinstance(value, int | float) else 0.0
    return seconds if 0.0 < seconds < float("inf") else 0.0


def _optional(value: Any) -> str | None:
    return None if value is None else str(value)


def _strings(value: Any) -> list[str]:
    return [str(v) for v in value] if isinstance(value, list) else []


def _entries(value: Any) -> list[Mapping[str, Any]]:
    return [v for v in value if isinstance(v, dict)] if isinstance(value, list) else []


def _pairs(value: Any) -> list[tuple[str, Any]]:
    if not isinstance(value, list):
        return []
    return [(str(v[0]), v[1]) for v in value if isinstance(v, list) and len(v) == 2]
