"""The substitutions a launch file uses, under ROS 2's names."""

from .boolean_substitution import AndSubstitution, NotSubstitution, OrSubstitution
from .environment_variable import EnvironmentVariable
from .find_executable import FindExecutable
from .launch_configuration import LaunchConfiguration
from .path_join_substitution import PathJoinSubstitution
from .python_expression import PythonExpression
from .substitution_failure import SubstitutionFailure
from .text_substitution import TextSubstitution
from .this_launch_file import ThisLaunchFile, ThisLaunchFileDir

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
