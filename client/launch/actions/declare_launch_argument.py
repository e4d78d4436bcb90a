"""``DeclareLaunchArgument('name', default_value=...)``: an argument of the launch file."""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING, Any, Optional

from launch.action import Action
from launch.utilities import perform_typed

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext
    from launch.launch_description_entity import LaunchDescriptionEntity


class DeclareLaunchArgument(Action):
    def __init__(
        self,
        name: str,
        *,
        default_value: Any = None,
        description: str | None = None,
        choices: Iterable[str] | None = None,
        **kwargs: Any,
    ) -> None:
        super().__init__(**kwargs)
        if not isinstance(name, str) or not name:
            raise TypeError(f"DeclareLaunchArgument's name must be a non-empty str, got {name!r}")
        self.__name = name
        self.__default_value = default_value
        self.__description = description or "no description given"
        self.__choices = None if choices is None else [str(c) for c in choices]

    @property
    def name(self) -> str:
        return self.__name

    @property
    def default_value(self) -> Any:
        return self.__default_value

    @property
    def description(self) -> str:
        return self.__description

    @property
    def choices(self) -> list[str] | None:
        return self.__choices

    def execute(self, context: LaunchContext) -> Optional[list[LaunchDescriptionEntity]]:  # noqa: UP045
        if self.__name not in context.launch_configurations:
            if self.__default_value is None:
                raise RuntimeError(
                    f"required launch argument '{self.__name}' (description: '{self.__description}') "
                    "was not provided: give it as NAME:=VALUE"
                )
            context.launch_configurations[self.__name] = perform_typed(context, self.__default_value)
        value = str(context.launch_configurations[self.__name])
        if self.__choices is not None and value not in self.__choices:
            raise RuntimeError(
                f"argument '{self.__name}' is '{value}', which is not one of its choices: "
                + ", ".join(self.__choices)
            )
        file = context.current_launch_file or ""
        context.declared.setdefault(file, {})[self.__name] = value
        return None
