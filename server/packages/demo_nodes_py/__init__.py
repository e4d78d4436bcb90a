"""The demo_nodes_py package of ROS 2 (ros2/demos): the talker and listener of its tutorials."""
