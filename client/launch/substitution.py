"""A value known only when the launch runs: an argument's, a package's folder, a path joined."""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


class Substitution:
    """Becomes a string with ``perform(context)``."""

    def perform(self, context: LaunchContext) -> str:
        raise NotImplementedError(f"{type(self).__name__} does not say how to perform it")

    def describe(self) -> str:
        return f"{type(self).__name__}(...)"

    def __repr__(self) -> str:
        return self.describe()

    def __add__(self, other: object) -> list[object]:
        return [self, other]

    def __radd__(self, other: object) -> list[object]:
        return [other, self]
