"""``$(eval EXPR)`` in an XML or YAML launch file: a small Python expression, evaluated here without
``eval``. The file is a student's, read by the server itself, so only what launch files use is
understood: literals, ``True``/``False``/``None``, ``pi`` and ``e``, arithmetic, comparisons,
``and``/``or``/``not``, ``x if c else y``, and tuples or lists for ``in``. No name lookup, call,
attribute or power: nothing that reaches beyond the text or grows without bound.
"""

from __future__ import annotations

import ast
import math
import operator
from collections.abc import Callable
from typing import Any

from server.services.launch.substitutions import SubstitutionError

MAX_EXPRESSION_CHARS = 1000
MAX_STRING_CHARS = 10_000
NAMES: dict[str, Any] = {"True": True, "False": False, "None": None, "pi": math.pi, "e": math.e}
_BINARY: dict[type[ast.operator], Callable[[Any, Any], Any]] = {
    ast.Add: operator.add,
    ast.Sub: operator.sub,
    ast.Mult: operator.mul,
    ast.Div: operator.truediv,
    ast.FloorDiv: operator.floordiv,
    ast.Mod: operator.mod,
}
_COMPARE: dict[type[ast.cmpop], Callable[[Any, Any], Any]] = {
    ast.Eq: operator.eq,
    ast.NotEq: operator.ne,
    ast.Lt: operator.lt,
    ast.LtE: operator.le,
    ast.Gt: operator.gt,
    ast.GtE: operator.ge,
    ast.In: lambda a, b: a in b,
    ast.NotIn: lambda a, b: a not in b,
}
_UNARY: dict[type[ast.unaryop], Callable[[Any], Any]] = {
    ast.Not: operator.not_,
    ast.USub: operator.neg,
    ast.UAdd: operator.pos,
}


def evaluate_expression(text: str) -> str:
    """``str()`` of the expression's value, as ROS 2's ``$(eval)`` gives it; SubstitutionError if it
    is not one this evaluator takes, or fails."""
    if len(text) > MAX_EXPRESSION_CHARS:
        raise SubstitutionError(f"$(eval) expression is longer than {MAX_EXPRESSION_CHARS} characters")
    try:
        tree = ast.parse(text.strip(), mode="eval")
        return str(_value(tree.body))
    except SyntaxError as err:
        raise SubstitutionError(f"$(eval '{text}') is not a Python expression: {err.msg}") from None
    except (ArithmeticError, TypeError, ValueError, RecursionError, MemoryError) as err:
        if isinstance(err, SubstitutionError):
            raise
        raise SubstitutionError(f"$(eval '{text}') failed: {type(err).__name__}: {err}") from None


def _value(node: ast.expr) -> Any:
    if isinstance(node, ast.Constant) and isinstance(node.value, bool | int | float | str | None):
        return node.value
    if isinstance(node, ast.Name):
        if node.id not in NAMES:
            raise SubstitutionError(
                f"$(eval) knows no name '{node.id}' (it takes literals, True, False, pi, e)"
            )
        return NAMES[node.id]
    if isinstance(node, ast.BoolOp):
        result = _value(node.values[0])
        for operand in node.values[1:]:
            if (not result) if isinstance(node.op, ast.And) else bool(result):
                break
            result = _value(operand)
        return result
    if isinstance(node, ast.UnaryOp) and type(node.op) in _UNARY:
        return _UNARY[type(node.op)](_value(node.operand))
    if isinstance(node, ast.BinOp) and type(node.op) in _BINARY:
        return _binary(type(node.op), _value(node.left), _value(node.right))
    if isinstance(node, ast.Compare):
        left = _value(node.left)
        for op, comparator in zip(node.ops, node.comparators, strict=True):
            right = _value(comparator)
            if not _COMPARE[type(op)](left, right):
                return False
            left = right
        return True
    if isinstance(node, ast.IfExp):
        return _value(node.body) if _value(node.test) else _value(node.orelse)
    if isinstance(node, ast.Tuple | ast.List):
        return tuple(_value(item) for item in node.elts)
    raise SubstitutionError(f"$(eval) does not take {type(node).__name__} here ({ast.unparse(node)!r})")


def _binary(op: type[ast.operator], left: Any, right: Any) -> Any:
    if op is ast.Mult and (isinstance(left, str | tuple) or isinstance(right, str | tuple)):
        raise SubstitutionError("$(eval) does not repeat strings or tuples")
    result = _BINARY[op](left, right)
    if isinstance(result, str | tuple) and len(result) > MAX_STRING_CHARS:
        raise SubstitutionError(f"$(eval) made a value longer than {MAX_STRING_CHARS}")
    return result
