"""``IfCondition`` and ``UnlessCondition``: an action runs when a value is true (or false)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from launch.condition import Condition
from launch.utilities import perform_typed

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


class InvalidConditionExpressionError(ValueError):
    pass


def evaluate_condition_expression(context: LaunchContext, expression: Any) -> bool:
    text = perform_typed(context, expression)
    lowered = text.strip().lower()
    if lowered in ("true", "1"):
        return True
    if lowered in ("false", "0"):
        return False
    raise InvalidConditionExpressionError(
        f"the condition '{text}' is not a boolean: it must be true, false, 1 or 0 (any case)"
    )


class IfCondition(Condition):
    def __init__(self, predicate_expression: Any) -> None:
        self.__expression = predicate_expression
        super().__init__(predicate=self._predicate_func)

    def _predicate_func(self, context: LaunchContext) -> bool:
        return evaluate_condition_expression(context, self.__expression)


class UnlessCondition(Condition):
    def __init__(self, predicate_expression: Any) -> None:
        self.__expression = predicate_expression
        super().__init__(predicate=self._predicate_func)

    def _predicate_func(self, context: LaunchContext) -> bool:
        return not evaluate_condition_expression(context, self.__expression)


class LaunchConfigurationEquals(Condition):
    def __init__(self, launch_configuration_name: str, expected_value: Any) -> None:
        self.__name, self.__expected = launch_configuration_name, expected_value
        super().__init__(predicate=self._predicate_func)

    def _predicate_func(self, context: LaunchContext) -> bool:
        value = context.launch_configurations.get(self.__name)
        expected = None if self.__expected is None else perform_typed(context, self.__expected)
        return value == expected


class LaunchConfigurationNotEquals(LaunchConfigurationEquals):
    def _predicate_func(self, context: LaunchContext) -> bool:
        return not super()._predicate_func(context)


__all__ = [
    "IfCondition",
    "InvalidConditionExpressionError",
    "LaunchConfigurationEquals",
    "LaunchConfigurationNotEquals",
    "UnlessCondition",
    "evaluate_condition_expression",
]
