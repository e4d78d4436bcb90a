"""The actions of a launch description, under ROS 2's names."""

from launch.actions.declare_launch_argument import DeclareLaunchArgument
from launch.actions.group_action import (
    GroupAction,
    PopLaunchConfigurations,
    PushLaunchConfigurations,
    ResetLaunchConfigurations,
)
from launch.actions.include_launch_description import IncludeLaunchDescription
from launch.actions.set_launch_configuration import SetLaunchConfiguration, UnsetLaunchConfiguration
from launch.actions.simple_actions import (
    ExecuteProcess,
    LogInfo,
    OpaqueFunction,
    SetEnvironmentVariable,
    TimerAction,
)

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
