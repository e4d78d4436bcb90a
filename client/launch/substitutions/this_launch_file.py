"""``ThisLaunchFile()`` and ``ThisLaunchFileDir()``: the launch file being read, and its folder."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

from launch.substitution import Substitution
from launch.substitutions.substitution_failure import SubstitutionFailure

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


class ThisLaunchFile(Substitution):
    def perform(self, context: LaunchContext) -> str:
        current = context.current_launch_file
        if current is None:
            raise SubstitutionFailure("ThisLaunchFile used outside a launch file")
        return current


class ThisLaunchFileDir(Substitution):
    def perform(self, context: LaunchContext) -> str:
        current = context.current_launch_file
        if current is None:
            raise SubstitutionFailure("ThisLaunchFileDir used outside a launch file")
        return os.path.dirname(current)
