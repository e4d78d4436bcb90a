"""``SetLaunchConfiguration(name, value)`` (``<let>`` in XML) and ``UnsetLaunchConfiguration``."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Optional

from launch.action import Action
from launch.utilities import perform_typed

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext
    from launch.launch_description_entity import LaunchDescriptionEntity


class SetLaunchConfiguration(Action):
    def __init__(self, name: Any, value: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.__name, self.__value = name, value

    def execute(self, context: LaunchContext) -> Optional[list[LaunchDescriptionEntity]]:  # noqa: UP045
        context.launch_configurations[perform_typed(context, self.__name)] = perform_typed(
            context, self.__value
        )
        return None


class UnsetLaunchConfiguration(Action):
    def __init__(self, name: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.__name = name

    def execute(self, context: LaunchContext) -> Optional[list[LaunchDescriptionEntity]]:  # noqa: UP045
        context.launch_configurations.pop(perform_typed(context, self.__name), None)
        return None
