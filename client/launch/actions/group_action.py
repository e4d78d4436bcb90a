"""``GroupAction([...])``: actions whose launch configurations (arguments, a pushed namespace,
remaps, parameters) stay inside the group."""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING, Any, Optional

from launch.action import Action
from launch.utilities import perform_typed

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext
    from launch.launch_description_entity import LaunchDescriptionEntity


class PushLaunchConfigurations(Action):
    def execute(self, context: LaunchContext) -> Optional[list[LaunchDescriptionEntity]]:  # noqa: UP045
        context.push_launch_configurations()
        return None


class PopLaunchConfigurations(Action):
    def execute(self, context: LaunchContext) -> Optional[list[LaunchDescriptionEntity]]:  # noqa: UP045
        context.pop_launch_configurations()
        return None


class ResetLaunchConfigurations(Action):
    def __init__(self, launch_configurations: dict[Any, Any] | None = None, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.__configurations = launch_configurations

    def execute(self, context: LaunchContext) -> Optional[list[LaunchDescriptionEntity]]:  # noqa: UP045
        kept = {
            perform_typed(context, k): perform_typed(context, v)
            for k, v in (self.__configurations or {}).items()
        }
        context.launch_configurations.clear()
        context.launch_configurations.update(kept)
        return None


class GroupAction(Action):
    def __init__(
        self,
        actions: Iterable[Action],
        *,
        scoped: bool = True,
        forwarding: bool = True,
        launch_configurations: dict[Any, Any] | None = None,
        **kwargs: Any,
    ) -> None:
        super().__init__(**kwargs)
        self.__actions = list(actions)
        self.__scoped = scoped
        self.__forwarding = forwarding
        self.__configurations = launch_configurations or {}

    def get_sub_entities(self) -> list[Action]:
        return list(self.__actions)

    def describe_sub_entities(self) -> list[LaunchDescriptionEntity]:
        return list(self.__actions)

    def execute(self, context: LaunchContext) -> Optional[list[LaunchDescriptionEntity]]:  # noqa: UP045
        settings: list[LaunchDescriptionEntity] = []
        if not self.__forwarding:
            settings.append(ResetLaunchConfigurations(self.__configurations))
        else:
            for name, value in self.__configurations.items():
                from launch.actions.set_launch_configuration import SetLaunchConfiguration

                settings.append(SetLaunchConfiguration(name, value))
        if not self.__scoped:
            return [*settings, *self.__actions]
        return [PushLaunchConfigurations(), *settings, *self.__actions, PopLaunchConfigurations()]
