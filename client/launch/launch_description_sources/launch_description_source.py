"""Where an included launch description comes from: a Python file, read here, or an XML or YAML
file, which the lab's launcher reads (in the same frontend as a file it launches)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from launch.action import Action
from launch.utilities import perform_typed

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext
    from launch.launch_description_entity import LaunchDescriptionEntity

MAX_INCLUDE_DEPTH = 32
MAX_FILES_READ = 256
ROS_SETTINGS = ("ros_namespace", "ros_remaps", "global_params")  # launch_ros's, not arguments


class LaunchDescriptionSource:
    def __init__(self, launch_file_path: Any = None, method: str = "a launch file") -> None:
        self.__location = launch_file_path
        self.__method = method

    @property
    def location(self) -> Any:
        return self.__location

    @property
    def method(self) -> str:
        return self.__method

    def resolve(self, context: LaunchContext) -> str:
        return perform_typed(context, self.__location)

    def include(
        self, context: LaunchContext, passed: dict[str, str], action: Action
    ) -> list[LaunchDescriptionEntity]:
        path = self.resolve(context)
        return (
            include_python(context, path)
            if path.endswith(".py")
            else include_frontend(context, path, passed, action)
        )


def include_python(context: LaunchContext, path: str) -> list[LaunchDescriptionEntity]:
    """The file's description, visited with ``ThisLaunchFile`` naming it; a cycle, too deep a
    chain or too many files is refused."""
    from launch.launch_description_sources.python_launch_file_utilities import (
        InvalidPythonLaunchFileError,
        get_launch_description_from_python_launch_file,
    )

    stack: list[str] = context.locals.setdefault("include_stack", [])
    if path in stack:
        raise InvalidPythonLaunchFileError(f"include cycle: {' -> '.join([*stack, path])}")
    if len(stack) >= MAX_INCLUDE_DEPTH:
        raise InvalidPythonLaunchFileError(f"includes are nested more than {MAX_INCLUDE_DEPTH} deep")
    context.locals["files_read"] = context.locals.get("files_read", 0) + 1
    if context.locals["files_read"] > MAX_FILES_READ:
        raise InvalidPythonLaunchFileError(f"more than {MAX_FILES_READ} files included in one launch")
    if path not in context.files:
        context.files.append(path)
    _Enter(path).execute(context)  # generate_launch_description() may use ThisLaunchFile too
    try:
        description = get_launch_description_from_python_launch_file(path)
    finally:
        _Leave().execute(context)
    return [_Enter(path), description, _Leave()]


def include_frontend(
    context: LaunchContext, path: str, passed: dict[str, str], action: Action
) -> list[LaunchDescriptionEntity]:
    """An XML or YAML file: the launcher reads it, at this point of the launch, with the namespace
    pushed here."""
    where = action.written_at or (context.current_launch_file or "", 0)
    # As in ROS 2, the included file's arguments also take the includer's launch configurations.
    inherited = {
        k: v for k, v in context.launch_configurations.items() if isinstance(v, str) and k not in ROS_SETTINGS
    }
    entry: dict[str, Any] = {
        "kind": "include",
        "file": path,
        "args": passed,
        "inherited": inherited,
        "namespace": context.launch_configurations.get("ros_namespace"),
        "at": {"file": where[0], "line": where[1]},
    }
    context.found.append(entry)
    return []


class _Enter(Action):
    """The start of an included file's actions: ``ThisLaunchFile`` names it until its end."""

    def __init__(self, path: str) -> None:
        super().__init__()
        self.path = path

    def execute(self, context: LaunchContext) -> None:
        context.locals.setdefault("include_stack", []).append(self.path)
        context.locals["current_launch_file_path"] = self.path


class _Leave(Action):
    def execute(self, context: LaunchContext) -> None:
        stack: list[str] = context.locals.setdefault("include_stack", [])
        stack.pop()
        context.locals["current_launch_file_path"] = stack[-1] if stack else None
