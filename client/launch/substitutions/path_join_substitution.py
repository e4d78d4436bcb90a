"""``PathJoinSubstitution([a, 'launch', b])``: path parts joined with the system's separator."""

from __future__ import annotations

import os
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from launch.substitution import Substitution
from launch.utilities import perform_typed

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


class PathJoinSubstitution(Substitution):
    def __init__(self, substitutions: Iterable[Any]) -> None:
        self.__parts = list(substitutions)

    @property
    def substitutions(self) -> list[Any]:
        return self.__parts

    def describe(self) -> str:
        return f"PathJoin({self.__parts!r})"

    def perform(self, context: LaunchContext) -> str:
        return os.path.join(*(perform_typed(context, part) for part in self.__parts)) if self.__parts else ""

    def __truediv__(self, other: Any) -> PathJoinSubstitution:
        return PathJoinSubstitution([*self.__parts, other])
