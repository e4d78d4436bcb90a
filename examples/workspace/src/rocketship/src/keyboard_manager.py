#!/usr/bin/env python
# Lab 2, part 1: a keyboard manager that aborts the rocket when "a" is pressed.
# Written as for ROS 2: the app provides rclpy, std_msgs and keyboard_msgs to this file.
import rclpy
from keyboard_msgs.msg import Key
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from std_msgs.msg import Bool


class KeyboardManager(Node):
    def __init__(self):
        super().__init__("KeyboardManagerNode")
        self.abort_pub = self.create_publisher(Bool, "/abort_takeoff", 1)
        self.key_sub = self.create_subscription(Key, "/keydown", self.get_key, 1)
        self.abort = Bool()
        self.key_code = -1
        self.timer = self.create_timer(1 / 10, self.process_key_code)  # 10 Hz

    def get_key(self, msg):
        # Keep callbacks short: remember the key, decide in the timer.
        self.key_code = msg.code

    def process_key_code(self):
        if self.key_code == Key.KEY_A:
            self.get_logger().info("a key was pressed!")
            self.abort.data = True
        self.abort_pub.publish(self.abort)
        self.key_code = -1


if __name__ == "__main__":
    rclpy.init()
    try:
        rclpy.spin(KeyboardManager())
    except (ExternalShutdownException, KeyboardInterrupt):
        pass
    finally:
        rclpy.try_shutdown()
