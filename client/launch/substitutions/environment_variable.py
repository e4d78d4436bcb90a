"""``EnvironmentVariable('NAME', default_value=...)``: a variable of the launch's environment."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from launch.substitution import Substitution
from launch.substitutions.substitution_failure import SubstitutionFailure
from launch.utilities import perform_typed

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


class EnvironmentVariable(Substitution):
    def __init__(self, name: Any, *, default_value: Any = None) -> None:
        self.__name = name
        self.__default = default_value

    @property
    def name(self) -> Any:
        return self.__name

    def describe(self) -> str:
        return f"EnvVar({self.__name!r})"

    def perform(self, context: LaunchContext) -> str:
        name = perform_typed(context, self.__name)
        value = context.environment.get(name)
        if value is not None:
            return value
        if self.__default is None:
            raise SubstitutionFailure(f"environment variable '{name}' does not exist")
        return perform_typed(context, self.__default)
