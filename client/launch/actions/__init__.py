"""The actions of a launch description, under ROS 2's names."""

from .declare_launch_argument import DeclareLaunchArgument
from .group_action import (
    GroupAction,
    PopLaunchConfigurations,
    PushLaunchConfigurations,
    ResetLaunchConfigurations,
)
from .include_launch_description import IncludeLaunchDescription
from .set_launch_configuration import SetLaunchConfiguration, UnsetLaunchConfiguration
from .simple_actions import ExecuteProcess, LogInfo, OpaqueFunction, SetEnvironmentVariable, TimerAction

__all__ = [
    "DeclareLaunchArgument",
    "ExecuteProcess",
    "GroupAction",
    "IncludeLaunchDescription",
    "LogInfo",
    "OpaqueFunction",
    "PopLaunchConfigurations",
    "PushLaunchConfigurations",
    "ResetLaunchConfigurations",
    "SetEnvironmentVariable",
    "SetLaunchConfiguration",
    "TimerAction",
    "UnsetLaunchConfiguration",
]
