"""``$(name arg ...)`` substitutions in launch XML attributes: the syntax, with nesting and quotes.

What each name resolves to is the evaluator's business (it holds the variables, the package
index and the environment); this module parses and checks the syntax and arity.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from types import MappingProxyType


class SubstitutionError(ValueError):
    """A substitution cannot be parsed or resolved; the caller adds file and line."""


_SUBSTITUTION_NAME = re.compile(r"[A-Za-z][A-Za-z0-9_-]*")
_SUPPORTED = ("var", "find-pkg-share", "env", "dirname", "eval")
_UNSUPPORTED_HINTS: Mapping[str, str] = MappingProxyType(
    {
        "arg": "$(arg NAME) is ROS 1 syntax; ROS 2 writes $(var NAME)",
        "find": "$(find PKG) is ROS 1 syntax; ROS 2 writes $(find-pkg-share PKG)",
        "optenv": "$(optenv NAME DEFAULT) is ROS 1 syntax; ROS 2 writes $(env NAME DEFAULT)",
    }
)
Resolve = Callable[[str, list[str]], str]


def substitute(text: str, resolve: Resolve) -> str:
    """Expand every ``$(name arg ...)`` in ``text``; arguments may nest substitutions or be quoted."""
    return _expand(text, 0, resolve, in_argument=False)[0]


def _expand(text: str, pos: int, resolve: Resolve, *, in_argument: bool) -> tuple[str, int]:
    parts: list[str] = []
    while pos < len(text):
        if text.startswith("$(", pos):
            value, pos = _expand_one(text, pos + 2, resolve)
            parts.append(value)
        elif in_argument and (text[pos].isspace() or text[pos] == ")"):
            break
        else:
            parts.append(text[pos])
            pos += 1
    return "".join(parts), pos


def _expand_one(text: str, pos: int, resolve: Resolve) -> tuple[str, int]:
    start = pos - 2
    match = _SUBSTITUTION_NAME.match(text, pos)
    if match is None:
        raise SubstitutionError(f"expected a substitution name after '$(' in {text[start:]!r}")
    name, pos = match.group(), match.end()
    if name not in _SUPPORTED:
        supported = ", ".join(f"$({known})" for known in _SUPPORTED)
        raise SubstitutionError(
            _UNSUPPORTED_HINTS.get(name, f"unknown substitution $({name}); use {supported}")
        )
    args: list[str] = []
    while True:
        while pos < len(text) and text[pos].isspace():
            pos += 1
        if pos >= len(text):
            raise SubstitutionError(f"unterminated substitution {text[start:]!r}: missing ')'")
        if text[pos] == ")":
            return resolve(name, args), pos + 1
        if text[pos] in "'\"":
            close = text.find(text[pos], pos + 1)
            if close < 0:
                raise SubstitutionError(f"unterminated quote in {text[start:]!r}")
            args.append(text[pos + 1 : close])
            pos = close + 1
        else:
            arg, pos = _expand(text, pos, resolve, in_argument=True)
            args.append(arg)


def package_not_found(pkg: str, err: LookupError) -> str:
    detail = "" if isinstance(err, KeyError) else str(err)  # KeyError's str() is just the quoted key
    return detail if f"'{pkg}'" in detail else f"package '{pkg}' not found"


def arity(name: str, args: list[str], low: int, high: int) -> None:
    if not low <= len(args) <= high:
        expected = f"{low}" if low == high else f"{low} to {high}"
        raise SubstitutionError(f"$({name}) takes {expected} argument(s), got {len(args)}")
