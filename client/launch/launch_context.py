"""What a launch description is evaluated against: the launch configurations (arguments and
``let`` values, scoped by groups), the environment, and what the evaluation found so far."""

from __future__ import annotations

import os
from typing import Any


class LaunchContext:
    """The state an evaluation carries from one action to the next, as ROS 2's ``LaunchContext``.

    The lab evaluates a description once, in order, without an event loop: what it finds (the
    nodes to start, the XML or YAML files to include, the lines to show) is kept in ``found``.
    """

    def __init__(self, *, argv: list[str] | None = None, environment: dict[str, str] | None = None) -> None:
        self.argv = list(argv or [])
        self.launch_configurations: dict[str, Any] = {}
        self.environment: dict[str, str] = dict(os.environ if environment is None else environment)
        self.locals: dict[str, Any] = {}
        self._configuration_stack: list[dict[str, Any]] = []
        self.found: list[dict[str, Any]] = []  # nodes and includes, in launch order
        self.messages: list[str] = []  # LogInfo's lines and what the lab did not run
        self.declared: dict[str, dict[str, str]] = {}  # launch file -> argument -> value
        self.files: list[str] = []  # every launch file read, the first one first

    def push_launch_configurations(self) -> None:
        self._configuration_stack.append(dict(self.launch_configurations))

    def pop_launch_configurations(self) -> None:
        if not self._configuration_stack:
            raise RuntimeError("launch configurations popped more often than pushed")
        self.launch_configurations = self._configuration_stack.pop()

    def extend_locals(self, new_locals: dict[str, Any]) -> None:
        self.locals.update(new_locals)

    def get_locals_as_dict(self) -> dict[str, Any]:
        return dict(self.locals)

    def perform_substitution(self, substitution: Any) -> str:
        return str(substitution.perform(self))

    @property
    def current_launch_file(self) -> str | None:
        value = self.locals.get("current_launch_file_path")
        return None if value is None else str(value)
