"""The substitutions a launch file uses, under ROS 2's names."""

from launch.substitutions.boolean_substitution import AndSubstitution, NotSubstitution, OrSubstitution
from launch.substitutions.environment_variable import EnvironmentVariable
from launch.substitutions.find_executable import FindExecutable
from launch.substitutions.launch_configuration import LaunchConfiguration
from launch.substitutions.path_join_substitution import PathJoinSubstitution
from launch.substitutions.python_expression import PythonExpression
from launch.substitutions.substitution_failure import SubstitutionFailure
from launch.substitutions.text_substitution import TextSubstitution
from launch.substitutions.this_launch_file import ThisLaunchFile, ThisLaunchFileDir

__all__ = [
    "AndSubstitution",
    "EnvironmentVariable",
    "FindExecutable",
    "LaunchConfiguration",
    "NotSubstitution",
    "OrSubstitution",
    "PathJoinSubstitution",
    "PythonExpression",
    "SubstitutionFailure",
    "TextSubstitution",
    "ThisLaunchFile",
    "ThisLaunchFileDir",
]
