"""Anything a launch description holds: visiting it may give more entities to visit."""

from __future__ import annotations

from typing import TYPE_CHECKING, Optional

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


class LaunchDescriptionEntity:
    def visit(self, context: LaunchContext) -> Optional[list[LaunchDescriptionEntity]]:  # noqa: UP045
        return None

    def describe(self) -> str:
        return type(self).__name__

    def describe_sub_entities(self) -> list[LaunchDescriptionEntity]:
        return []
