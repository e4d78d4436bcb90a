"""ROS 2's sensor_msgs_py: ``point_cloud2`` reads and makes PointCloud2 messages with numpy."""
