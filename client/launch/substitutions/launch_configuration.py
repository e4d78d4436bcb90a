"""``LaunchConfiguration('name')``: an argument's value, or a ``let``/SetLaunchConfiguration's."""

from __future__ import annotations

import difflib
from typing import TYPE_CHECKING, Any

from launch.substitution import Substitution
from launch.substitutions.substitution_failure import SubstitutionFailure
from launch.utilities import perform_typed

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


class LaunchConfiguration(Substitution):
    def __init__(self, variable_name: Any, *, default: Any = None) -> None:
        self.__variable_name = variable_name
        self.__default = default

    @property
    def variable_name(self) -> Any:
        return self.__variable_name

    def describe(self) -> str:
        return f"LaunchConfig({self.__variable_name!r})"

    def perform(self, context: LaunchContext) -> str:
        name = perform_typed(context, self.__variable_name)
        if name in context.launch_configurations:
            return str(context.launch_configurations[name])
        if self.__default is not None:
            return perform_typed(context, self.__default)
        known = [k for k in context.launch_configurations if not k.startswith(("ros_", "global_"))]
        close = difflib.get_close_matches(name, known, n=1)
        hint = f"; did you mean '{close[0]}'?" if close else " (declare it with DeclareLaunchArgument first)"
        raise SubstitutionFailure(f"launch configuration '{name}' does not exist{hint}")
