"""``IncludeLaunchDescription(source, launch_arguments=...)``: another launch file's actions,
here, with the arguments given."""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING, Any, Optional

from launch.action import Action
from launch.launch_description_sources.launch_description_source import LaunchDescriptionSource
from launch.utilities import perform_typed

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext
    from launch.launch_description_entity import LaunchDescriptionEntity


class IncludeLaunchDescription(Action):
    def __init__(
        self,
        launch_description_source: Any,
        *,
        launch_arguments: Iterable[tuple[Any, Any]] | None = None,
        **kwargs: Any,
    ) -> None:
        super().__init__(**kwargs)
        if not isinstance(launch_description_source, LaunchDescriptionSource):
            from launch.launch_description_sources import AnyLaunchDescriptionSource

            launch_description_source = AnyLaunchDescriptionSource(launch_description_source)
        self.__source: LaunchDescriptionSource = launch_description_source
        pairs = list(launch_arguments or [])
        for pair in pairs:
            if not isinstance(pair, tuple | list) or len(pair) != 2:
                raise TypeError(
                    f"launch_arguments holds (name, value) pairs (a dict's .items()), got {pair!r}"
                )
        self.__launch_arguments = [(name, value) for name, value in pairs]

    @property
    def launch_description_source(self) -> LaunchDescriptionSource:
        return self.__source

    @property
    def launch_arguments(self) -> list[tuple[Any, Any]]:
        return self.__launch_arguments

    def execute(self, context: LaunchContext) -> Optional[list[LaunchDescriptionEntity]]:  # noqa: UP045
        passed = {
            perform_typed(context, name): perform_typed(context, value)
            for name, value in self.__launch_arguments
        }
        context.launch_configurations.update(passed)  # as ROS 2 does: the includer sees them too
        return self.__source.include(context, passed, self)
