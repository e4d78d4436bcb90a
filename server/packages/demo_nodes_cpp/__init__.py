"""The demo_nodes_cpp package of ROS 2 (ros2/demos), as Python nodes with its names, topics and
log lines: the talker of "Integrating launch files" and the listener beside it."""
