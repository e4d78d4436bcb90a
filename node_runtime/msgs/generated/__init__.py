"""The message and service classes, one module per ROS package (see node_runtime/msgs/generate.py);
a module is imported when one of its types is first asked for (node_runtime/msgs/_base.py's
load_generated), so a process declares only the classes it uses."""

PACKAGES = (
    "action_msgs",
    "action_tutorials_interfaces",
    "actionlib_msgs",
    "builtin_interfaces",
    "diagnostic_msgs",
    "example_interfaces",
    "geometry_msgs",
    "keyboard_msgs",
    "lifecycle_msgs",
    "nav_msgs",
    "rcl_interfaces",
    "rosapi_msgs",
    "rosgraph_msgs",
    "sensor_msgs",
    "service_msgs",
    "shape_msgs",
    "std_msgs",
    "std_srvs",
    "stereo_msgs",
    "tf2_msgs",
    "trajectory_msgs",
    "turtlesim",
    "type_description_interfaces",
    "unique_identifier_msgs",
    "visualization_msgs",
)
