"""``PythonExpression(['1 + ', LaunchConfiguration('x')])``: the text, evaluated as Python."""

from __future__ import annotations

import importlib
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from launch.substitution import Substitution
from launch.substitutions.substitution_failure import SubstitutionFailure
from launch.utilities import perform_typed

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


class PythonExpression(Substitution):
    def __init__(self, expression: Any, python_modules: Iterable[Any] = ("math",)) -> None:
        self.__expression = expression
        self.__modules = list(python_modules)

    @property
    def expression(self) -> Any:
        return self.__expression

    def describe(self) -> str:
        return f"PythonExpr({self.__expression!r})"

    def perform(self, context: LaunchContext) -> str:
        names: dict[str, Any] = {}
        for module in self.__modules:
            name = perform_typed(context, module)
            imported = importlib.import_module(name)
            names[name] = imported
            if name == "math":  # as ROS 2 does: math's names bare too
                names.update({k: v for k, v in vars(imported).items() if not k.startswith("_")})
        text = perform_typed(context, self.__expression)
        try:
            return str(eval(text, names))
        except Exception as exc:
            raise SubstitutionFailure(f"PythonExpression {text!r}: {type(exc).__name__}: {exc}") from None
