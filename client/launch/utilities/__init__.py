"""Turning what a launch file passes (strings, substitutions, lists of them) into strings."""

from __future__ import annotations

import os
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from launch.substitution import Substitution

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


def normalize_to_list_of_substitutions(subs: Any) -> list[Substitution]:
    """A string, a substitution or a (nested) sequence of them as a flat list of substitutions."""
    from launch.substitutions.text_substitution import TextSubstitution

    def one(item: Any) -> Substitution:
        if isinstance(item, Substitution):
            return item
        if isinstance(item, str | os.PathLike):
            return TextSubstitution(text=os.fspath(item))
        if isinstance(item, bool | int | float):
            return TextSubstitution(text=str(item))
        raise TypeError(f"expected a string or a substitution, got {type(item).__name__}: {item!r}")

    if isinstance(subs, str | Substitution | os.PathLike | bool | int | float):
        return [one(subs)]
    if isinstance(subs, Iterable):
        out: list[Substitution] = []
        for item in subs:
            out.extend(normalize_to_list_of_substitutions(item) if _is_sequence(item) else [one(item)])
        return out
    raise TypeError(f"expected a string, a substitution or a list of them, got {type(subs).__name__}")


def _is_sequence(item: Any) -> bool:
    return isinstance(item, Iterable) and not isinstance(item, str | bytes | Substitution)


def perform_substitutions(context: LaunchContext, subs: Iterable[Substitution]) -> str:
    return "".join(context.perform_substitution(sub) for sub in subs)


def perform_typed(context: LaunchContext, value: Any) -> str:
    """``value`` (anything SomeSubstitutionsType allows) performed to one string."""
    return perform_substitutions(context, normalize_to_list_of_substitutions(value))


def is_a_subclass(obj: Any, entity_type: type) -> bool:
    return isinstance(obj, type) and issubclass(obj, entity_type)


def ensure_argument_type(argument: Any, types: Any, argument_name: str, caller: str = "") -> None:
    if not isinstance(argument, types):
        raise TypeError(
            f"{caller + ': ' if caller else ''}'{argument_name}' is a {type(argument).__name__}, not {types}"
        )


__all__ = [
    "ensure_argument_type",
    "is_a_subclass",
    "normalize_to_list_of_substitutions",
    "perform_substitutions",
    "perform_typed",
]
