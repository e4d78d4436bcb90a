"""``FindExecutable(name='python3')``: a program's path on the launch's PATH."""

from __future__ import annotations

import shutil
from typing import TYPE_CHECKING, Any

from launch.substitution import Substitution
from launch.substitutions.substitution_failure import SubstitutionFailure
from launch.utilities import perform_typed

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


class FindExecutable(Substitution):
    def __init__(self, *, name: Any) -> None:
        self.__name = name

    def perform(self, context: LaunchContext) -> str:
        name = perform_typed(context, self.__name)
        found = shutil.which(name, path=context.environment.get("PATH"))
        if found is None:
            raise SubstitutionFailure(f"executable '{name}' not found on the PATH")
        return found
