"""The types an argument that takes substitutions accepts: a string, a substitution, or a
sequence of either (concatenated)."""

from __future__ import annotations

from collections.abc import Iterable

from launch.substitution import Substitution

SomeSubstitutionsType = str | Substitution | Iterable[str | Substitution]
SomeSubstitutionsType_types_tuple = (str, Substitution)

__all__ = ["SomeSubstitutionsType", "SomeSubstitutionsType_types_tuple"]
