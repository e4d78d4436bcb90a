"""``LaunchDescription([...])``: what ``generate_launch_description()`` returns."""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING, Optional

from launch.launch_description_entity import LaunchDescriptionEntity

if TYPE_CHECKING:
    from launch.actions.declare_launch_argument import DeclareLaunchArgument
    from launch.launch_context import LaunchContext


class LaunchDescription(LaunchDescriptionEntity):
    def __init__(
        self,
        initial_entities: Iterable[LaunchDescriptionEntity] | None = None,
        *,
        deprecated_reason: str | None = None,
    ) -> None:
        self.__entities = list(initial_entities or [])
        for entity in self.__entities:
            _check_entity(entity)
        self.deprecated_reason = deprecated_reason

    def visit(self, context: LaunchContext) -> Optional[list[LaunchDescriptionEntity]]:  # noqa: UP045
        return list(self.__entities)

    def describe_sub_entities(self) -> list[LaunchDescriptionEntity]:
        return list(self.__entities)

    @property
    def entities(self) -> list[LaunchDescriptionEntity]:
        return self.__entities

    def add_entity(self, entity: LaunchDescriptionEntity) -> None:
        _check_entity(entity)
        self.__entities.append(entity)

    def add_action(self, action: LaunchDescriptionEntity) -> None:
        self.add_entity(action)

    def get_launch_arguments(self, conditional_inclusion: bool = False) -> list[DeclareLaunchArgument]:
        """The arguments this description declares, in groups too (not in included files)."""
        from launch.actions.declare_launch_argument import DeclareLaunchArgument

        found: list[DeclareLaunchArgument] = []

        def walk(entities: Iterable[LaunchDescriptionEntity]) -> None:
            for entity in entities:
                if isinstance(entity, DeclareLaunchArgument):
                    found.append(entity)
                elif not isinstance(entity, LaunchDescription):
                    walk(entity.describe_sub_entities())

        walk(self.__entities)
        return found


def _check_entity(entity: object) -> None:
    if not isinstance(entity, LaunchDescriptionEntity):
        raise TypeError(
            f"LaunchDescription takes actions (Node, DeclareLaunchArgument, ...), got "
            f"{type(entity).__name__}: {entity!r}"
        )
