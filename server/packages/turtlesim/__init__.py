"""The turtlesim package of ROS 2's tutorials (ros/ros_tutorials), headless: turtlesim_node, mimic."""
