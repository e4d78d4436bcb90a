"""``--ros-args`` as ``ros2 run`` and ``ros2 launch`` pass them: ``-r``/``--remap``, ``-p``/``--param``,
``--params-file``, ``--log-level``; ``__node``/``__ns`` remaps rename the node and its namespace.
A parameters file is read here, so one that does not parse stops ``rclpy.init()`` with one line
naming the file (and line)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

from node_runtime.params_file import ParamsFile, ParamsFileError, read_params_file

LOG_LEVELS = {"debug": 10, "info": 20, "warn": 30, "warning": 30, "error": 40, "fatal": 50}


class RosArgsError(ValueError):
    """An argument after ``--ros-args`` that rcl would refuse."""


@dataclass
class RosArgs:
    node_name: str | None = None
    namespace: str | None = None
    remappings: dict[str, str] = field(default_factory=dict)
    parameters: dict[str, Any] = field(default_factory=dict)
    params_files: list[ParamsFile] = field(default_factory=list)
    log_level: int | None = None  # the console's threshold (``--log-level``), as rcutils' severities
    rest: list[str] = field(default_factory=list)  # what is not a ROS argument (the program's own)

    def parameters_for(self, fully_qualified_name: str) -> dict[str, Any]:
        """A node's overrides: its sections of the parameters files, in order, then ``-p``."""
        out: dict[str, Any] = {}
        for params_file in self.params_files:
            out.update(params_file.for_node(fully_qualified_name))
        out.update(self.parameters)
        return out


def _value(text: str) -> Any:
    """A parameter value as rcl reads it: YAML (``5``, ``2.0``, ``true``, ``[1, 2]``, ``'text'``)."""
    import yaml  # only for a node given ``-p``: a node process without ROS arguments never loads it

    try:
        return yaml.safe_load(text)
    except yaml.YAMLError:
        return text


def _pair(flag: str, text: str) -> tuple[str, str]:
    name, sep, value = text.partition(":=")
    if not sep or not name:
        raise RosArgsError(f"{flag} takes FROM:=TO (or NAME:=VALUE), got {text!r}")
    return name, value


def parse_ros_args(argv: Sequence[str]) -> RosArgs:
    """Split ``argv`` (without the program name) into ROS arguments and the program's own."""
    out = RosArgs()
    i, inside = 0, False
    while i < len(argv):
        arg = argv[i]
        if arg == "--ros-args":
            inside = True
        elif arg == "--" and inside:
            inside = False
        elif not inside:
            out.rest.append(arg)
        elif arg in ("-r", "--remap", "-p", "--param", "--log-level"):
            if i + 1 >= len(argv):
                raise RosArgsError(f"{arg} needs a value")
            i += 1
            text = argv[i]
            if arg == "--log-level":
                level = text.split(":=")[-1].lower()  # ``name:=level`` sets one logger in ROS; here, all
                if level not in LOG_LEVELS:
                    raise RosArgsError(f"--log-level takes one of {', '.join(LOG_LEVELS)}, got {text!r}")
                out.log_level = LOG_LEVELS[level]
            elif arg in ("-r", "--remap"):
                rule = text
                target, sep, _ = text.partition(":=")
                if (
                    sep and ":" in target
                ):  # ``node_name:from:=to`` aims at one node; one node per process here
                    rule = text.split(":", 1)[1]
                name, value = _pair(arg, rule)
                if name in ("__node", "__name"):
                    out.node_name = value
                elif name == "__ns":
                    out.namespace = value
                else:
                    out.remappings[name] = value
            else:
                name, value = _pair(arg, text)
                out.parameters[name] = _value(value)
        elif arg == "--params-file":
            if i + 1 >= len(argv):
                raise RosArgsError(f"{arg} needs a value")
            i += 1
            try:
                out.params_files.append(read_params_file(argv[i]))
            except ParamsFileError as exc:
                raise RosArgsError(str(exc)) from None
        elif arg in ("-e", "--enclave"):
            i += 1  # accepted, not used by the lab
        else:
            raise RosArgsError(f"unknown ROS argument {arg!r}")
        i += 1
    return out
