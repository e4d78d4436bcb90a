"""``NotSubstitution``, ``AndSubstitution``, ``OrSubstitution``: booleans of other values."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from launch.substitution import Substitution
from launch.substitutions.substitution_failure import SubstitutionFailure
from launch.utilities import perform_typed

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


def truth(text: str) -> bool:
    lowered = text.strip().lower()
    if lowered in ("true", "1"):
        return True
    if lowered in ("false", "0"):
        return False
    raise SubstitutionFailure(f"'{text}' is not a boolean: use true, false, 1 or 0")


class NotSubstitution(Substitution):
    def __init__(self, value: Any) -> None:
        self.__value = value

    def perform(self, context: LaunchContext) -> str:
        return str(not truth(perform_typed(context, self.__value))).lower()


class AndSubstitution(Substitution):
    def __init__(self, left: Any, right: Any) -> None:
        self.__left, self.__right = left, right

    def perform(self, context: LaunchContext) -> str:
        return str(
            truth(perform_typed(context, self.__left)) and truth(perform_typed(context, self.__right))
        ).lower()


class OrSubstitution(Substitution):
    def __init__(self, left: Any, right: Any) -> None:
        self.__left, self.__right = left, right

    def perform(self, context: LaunchContext) -> str:
        return str(
            truth(perform_typed(context, self.__left)) or truth(perform_typed(context, self.__right))
        ).lower()
