"""What a launch file describes, as plain typed data: the nodes and commands to start, the arguments.

The front-ends (XML and YAML in ``xml_parser``, Python in ``python_launch``) produce these
values; the launcher executes them. Nothing here runs a node or touches the bus.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

from node_runtime.params_file import ParamsFile

ParamScalar = bool | int | float | str
"""A scalar ROS parameter value. ``bool`` is checked before ``int`` (Python's bool is an int)."""

ParamValue = ParamScalar | list[bool] | list[int] | list[float] | list[str]
"""A ROS parameter value: a scalar or a uniform list, as ``rclpy`` accepts them."""


class LaunchFileError(Exception):
    """A launch file is malformed, or asks for something that cannot be resolved.

    ``line`` is 1-based; 0 means the file as a whole (not found, too large, an argument given
    on the command line that the file does not declare).
    """

    def __init__(self, file: str, line: int, problem: str) -> None:
        super().__init__(file, line, problem)
        self.file = file
        self.line = line
        self.problem = problem

    def __str__(self) -> str:
        return f"{self.file}:{self.line}: {self.problem}"


@dataclass(frozen=True)
class SourceLocation:
    """Where an action was written: the launch file's path and the 1-based line of its element."""

    file: str
    line: int

    def __str__(self) -> str:
        return f"{self.file}:{self.line}"


@dataclass(frozen=True)
class NodeAction:
    """One ``<node>`` to start, with every substitution already performed.

    - ``exec``: the executable name inside ``pkg`` (``type`` in ROS 1 files).
    - ``name``: the node-name override, or ``None`` to keep the name the executable gives itself.
    - ``namespace``: the namespace after any enclosing ``<push-ros-namespace>``, or ``None`` when
      neither the node nor a group sets one. Not validated here; the bus validates names.
    - ``output``: ``"screen"``, ``"log"``, ``"both"``, ``"own_log"``, ``"full"`` or ``None``.
    - ``respawn_delay_s``: seconds to wait before restarting a node that exited (with ``respawn``).
    - ``parameters``: ``(name, value)`` in document order; nested ``<param>`` names joined by ``.``.
    - ``parameter_files``: the ``<param from=...>`` files, read, in document order; the node takes
      its sections of each, then ``parameters`` (which win over a file's, wherever written).
    - ``remappings``: ``(from, to)`` in document order.
    - ``shutdown_on_exit``: ``on_exit="shutdown"``: when this node exits, the whole launch ends.
    - ``arguments``, ``ros_arguments``: a Python launch file's ``Node(arguments=, ros_arguments=)``.
    """

    pkg: str
    exec: str
    name: str | None
    namespace: str | None
    output: str | None
    respawn: bool
    respawn_delay_s: float
    parameters: tuple[tuple[str, ParamValue], ...]
    remappings: tuple[tuple[str, str], ...]
    location: SourceLocation
    shutdown_on_exit: bool = False
    parameter_files: tuple[ParamsFile, ...] = ()
    arguments: tuple[str, ...] = ()  # a Python launch file's Node(arguments=...): before --ros-args
    ros_arguments: tuple[str, ...] = ()  # its Node(ros_arguments=...): after the lab's own ROS arguments
    start_delay_s: float = 0.0  # a Python file's TimerAction(period=...) around it: started that much later


@dataclass(frozen=True)
class CommandAction:
    """One command to run (a Python file's ``ExecuteProcess``, an XML or YAML ``executable``), every
    substitution performed. Which commands run, and how, is the launcher's business
    (server/services/launch/ros2_commands.py: ``ros2 ...`` only, as the lab's CLI).

    - ``cmd``: the words as written; with ``shell`` they are joined by spaces and split as a shell would.
    - ``name``: the label its output shows (``name-N``), or ``None`` for the program's name.
    - ``output``: as a node's (``"log"``: not printed on the server's console; the launch shows it).
    - ``start_delay_s``: a ``TimerAction`` / ``timer`` around it: started that much later.
    """

    cmd: tuple[str, ...]
    shell: bool
    name: str | None
    output: str | None
    location: SourceLocation
    start_delay_s: float = 0.0


@dataclass(frozen=True)
class LaunchDescription:
    """A launch file with its includes flattened.

    - ``nodes``: every node that survived its ``if``/``unless`` conditions, in document order,
      included files expanded in place.
    - ``args``: the top-level file's declared arguments with their final values (read-only).
    - ``files``: every file read, the top-level one first, each once, in the order first read.
    - ``messages``: lines to show with the launch: a Python file's ``LogInfo`` and what it printed.
    - ``commands``: the commands to run (``ExecuteProcess``, ``executable``), in document order.
    """

    nodes: tuple[NodeAction, ...]
    args: Mapping[str, str] = field(default_factory=lambda: MappingProxyType({}))
    files: tuple[str, ...] = ()
    messages: tuple[str, ...] = ()
    commands: tuple[CommandAction, ...] = ()
