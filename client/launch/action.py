"""An action of a launch description (start a node, declare an argument, include a file ...),
which remembers where the launch file made it, so a problem it meets later names that line."""

from __future__ import annotations

import sys
from pathlib import Path
from types import FrameType
from typing import TYPE_CHECKING, Optional

from launch.launch_description_entity import LaunchDescriptionEntity

if TYPE_CHECKING:
    from launch.condition import Condition
    from launch.launch_context import LaunchContext

# The folders of the launch packages themselves: a frame in them is never "where it was written".
_OURS = tuple(
    str(Path(__file__).resolve().parents[1] / name)
    for name in ("launch", "launch_ros", "launch_xml", "launch_yaml")
)


def written_at() -> tuple[str, int] | None:
    """The file and line of the nearest caller outside the launch packages."""
    frame: FrameType | None = sys._getframe(1)
    while frame is not None:
        name = frame.f_code.co_filename
        if not name.startswith(_OURS) and not name.startswith("<"):
            return name, frame.f_lineno
        frame = frame.f_back
    return None


class Action(LaunchDescriptionEntity):
    """Runs when visited unless its ``condition`` says not."""

    def __init__(self, *, condition: Condition | None = None) -> None:
        self.__condition = condition
        self.written_at = written_at()

    @property
    def condition(self) -> Condition | None:
        return self.__condition

    def visit(self, context: LaunchContext) -> Optional[list[LaunchDescriptionEntity]]:  # noqa: UP045
        if self.__condition is None or self.__condition.evaluate(context):
            return self.execute(context)
        return None

    def execute(self, context: LaunchContext) -> Optional[list[LaunchDescriptionEntity]]:  # noqa: UP045
        return None
