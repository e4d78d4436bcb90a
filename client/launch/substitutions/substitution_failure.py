"""A substitution that cannot be performed (an argument never declared, a variable not set)."""

from __future__ import annotations


class SubstitutionFailure(RuntimeError):
    pass
