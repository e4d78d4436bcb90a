"""ROS 2's ``launch`` for a lab: a ``.launch.py`` file's ``generate_launch_description()`` builds
the same actions, substitutions and conditions, under the same names.

The lab evaluates a description once, in a process of its own (``launch.lab_evaluation``), into
the nodes to start and the XML or YAML files to include; its launcher then starts them as it does
an XML launch file's.
"""

from launch import actions, conditions, launch_description_sources, substitutions
from launch.action import Action
from launch.condition import Condition
from launch.launch_context import LaunchContext
from launch.launch_description import LaunchDescription
from launch.launch_description_entity import LaunchDescriptionEntity
from launch.launch_description_sources import LaunchDescriptionSource
from launch.some_substitutions_type import SomeSubstitutionsType, SomeSubstitutionsType_types_tuple
from launch.substitution import Substitution

__all__ = [
    "Action",
    "Condition",
    "LaunchContext",
    "LaunchDescription",
    "LaunchDescriptionEntity",
    "LaunchDescriptionSource",
    "SomeSubstitutionsType",
    "SomeSubstitutionsType_types_tuple",
    "Substitution",
    "actions",
    "conditions",
    "launch_description_sources",
    "substitutions",
]
