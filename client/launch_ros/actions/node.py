"""``Node(package=, executable=, name=, namespace=, parameters=, remappings=, ...)``: a node the
launch starts; the lab's launcher starts it as it does an XML ``<node>``."""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any, Optional

from launch import Action, LaunchContext, LaunchDescriptionEntity
from launch.utilities import perform_typed

from launch_ros.namespaces import make_namespace_absolute, prefix_namespace
from launch_ros.parameters import evaluate_parameters, performed_value

OUTPUTS = ("screen", "log", "both", "own_log", "full")


class Node(Action):
    def __init__(
        self,
        *,
        executable: Any,
        package: Any = None,
        name: Any = None,
        namespace: Any = None,
        exec_name: Any = None,
        parameters: Iterable[Any] | None = None,
        remappings: Iterable[tuple[Any, Any]] | None = None,
        ros_arguments: Iterable[Any] | None = None,
        arguments: Iterable[Any] | None = None,
        output: Any = None,
        respawn: Any = False,
        respawn_delay: float | None = None,
        **kwargs: Any,
    ) -> None:
        for dropped in (
            "cwd",
            "env",
            "additional_env",
            "emulate_tty",
            "prefix",
            "sigterm_timeout",
            "sigkill_timeout",
            "on_exit",
            "log_cmd",
            "cached_output",
        ):
            kwargs.pop(dropped, None)  # how ROS 2 runs the process; the lab runs it its own way
        super().__init__(**kwargs)
        if package is None:
            raise TypeError("Node needs package= (the lab runs an executable of a package)")
        self.__package, self.__executable = package, executable
        self.__name, self.__namespace, self.__exec_name = name, namespace, exec_name
        self.__parameters = list(parameters or [])
        self.__remappings = [tuple(pair) for pair in (remappings or [])]
        for pair in self.__remappings:
            if len(pair) != 2:
                raise TypeError(f"remappings holds (from, to) pairs, got {pair!r}")
        self.__ros_arguments = list(ros_arguments or [])
        self.__arguments = list(arguments or [])
        self.__output = output
        self.__respawn = respawn
        self.__respawn_delay = respawn_delay

    @property
    def node_package(self) -> Any:
        return self.__package

    @property
    def node_executable(self) -> Any:
        return self.__executable

    @property
    def node_name(self) -> Any:
        return self.__name

    def execute(self, context: LaunchContext) -> Optional[list[LaunchDescriptionEntity]]:  # noqa: UP045
        name = None if self.__name is None else perform_typed(context, self.__name).lstrip("/")
        own_ns = None if self.__namespace is None else perform_typed(context, self.__namespace)
        namespace = make_namespace_absolute(
            prefix_namespace(context.launch_configurations.get("ros_namespace"), own_ns)
        )
        output = None if self.__output is None else perform_typed(context, self.__output)
        if output is not None and output not in OUTPUTS:
            raise RuntimeError(f"Node output='{output}' is not one of {', '.join(OUTPUTS)}")
        respawn = performed_value(context, self.__respawn)
        if isinstance(respawn, str):
            respawn = respawn.strip().lower() in ("true", "1")
        values = [
            (str(k), performed_value(context, v))
            for k, v in context.launch_configurations.get("global_params", [])
        ]
        own_values, files = evaluate_parameters(context, self.__parameters)
        remaps: list[tuple[str, str]] = list(context.launch_configurations.get("ros_remaps", []))
        remaps += [(perform_typed(context, a), perform_typed(context, b)) for a, b in self.__remappings]
        file, line = self.written_at or (context.current_launch_file or "", 0)
        entry: dict[str, Any] = {
            "kind": "node",
            "pkg": perform_typed(context, self.__package),
            "exec": perform_typed(context, self.__executable),
            "name": name,
            "namespace": namespace,
            "output": output,
            "respawn": bool(respawn),
            "respawn_delay": float(self.__respawn_delay or 0.0),
            "parameters": [list(p) for p in (*values, *own_values)],
            "parameter_files": files,
            "remappings": [list(r) for r in remaps],
            "arguments": [perform_typed(context, a) for a in self.__arguments],
            "ros_arguments": [perform_typed(context, a) for a in self.__ros_arguments],
            "file": file,
            "line": line,
            "start_delay": float(context.locals.get("start_delay_s", 0.0)),
        }
        context.found.append(entry)
        return None
