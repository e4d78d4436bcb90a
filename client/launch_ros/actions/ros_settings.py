"""What a group (or the rest of a launch file) gives every node after it: ``PushRosNamespace``,
``SetRemap``, ``SetParameter``. Each is a launch configuration, so a ``GroupAction`` scopes it."""

from __future__ import annotations

from typing import Any, Optional

from launch import Action, LaunchContext, LaunchDescriptionEntity
from launch.utilities import perform_typed

from launch_ros.namespaces import make_namespace_absolute, prefix_namespace
from launch_ros.parameters import performed_value


class PushRosNamespace(Action):
    def __init__(self, namespace: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.__namespace = namespace

    @property
    def namespace(self) -> Any:
        return self.__namespace

    def execute(self, context: LaunchContext) -> Optional[list[LaunchDescriptionEntity]]:  # noqa: UP045
        pushed = perform_typed(context, self.__namespace)
        previous = context.launch_configurations.get("ros_namespace")
        context.launch_configurations["ros_namespace"] = make_namespace_absolute(
            prefix_namespace(previous, pushed)
        )
        return None


PushROSNamespace = PushRosNamespace


class SetRemap(Action):
    def __init__(self, src: Any, dst: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.__src, self.__dst = src, dst

    def execute(self, context: LaunchContext) -> Optional[list[LaunchDescriptionEntity]]:  # noqa: UP045
        remaps = list(context.launch_configurations.get("ros_remaps", []))
        remaps.append((perform_typed(context, self.__src), perform_typed(context, self.__dst)))
        context.launch_configurations["ros_remaps"] = remaps
        return None


class SetParameter(Action):
    def __init__(self, name: Any, value: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.__name, self.__value = name, value

    def execute(self, context: LaunchContext) -> Optional[list[LaunchDescriptionEntity]]:  # noqa: UP045
        params = list(context.launch_configurations.get("global_params", []))
        params.append((perform_typed(context, self.__name), performed_value(context, self.__value)))
        context.launch_configurations["global_params"] = params
        return None
