"""The keyboard package (after cmower/ros2-keyboard): key presses in, keyboard_msgs/Key out."""
