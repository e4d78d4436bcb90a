"""Whether an action runs: ``condition=IfCondition(...)`` on any action."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


class Condition:
    def __init__(self, *, predicate: Callable[[LaunchContext], bool] | None = None) -> None:
        self._predicate = predicate

    def evaluate(self, context: LaunchContext) -> bool:
        return True if self._predicate is None else bool(self._predicate(context))

    def describe(self) -> str:
        return type(self).__name__
