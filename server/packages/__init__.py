"""The lab's ROS packages as Python nodes: each folder is a package, with its ``launch/`` folder.

Which ``(pkg, exec)`` names which node is ``node_runtime.ament.index``."""
