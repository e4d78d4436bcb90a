#!/usr/bin/env python
# Lab 2, part 2: fly the drone with the arrow keys, one metre per press.
import time

import rclpy
from geometry_msgs.msg import Vector3
from keyboard_msgs.msg import Key
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node


class KeyboardManager(Node):
    def __init__(self):
        super().__init__("KeyboardManagerNode")
        self.position_pub = self.create_publisher(Vector3, "/uav/input/position", 1)
        self.keyboard_sub = self.create_subscription(Key, "/keydown", self.get_key, 1)
        self.pos = Vector3()
        self.pos.x, self.pos.y, self.pos.z = 0.0, 0.0, 3.0  # hover over the centre
        self.key_code = -1
        time.sleep(10)  # as in the handout; the app skips it, since it would block every node
        self.rate = 20
        self.timer = self.create_timer(1.0 / self.rate, self.mainloop)

    def get_key(self, msg):
        self.key_code = msg.code

    def mainloop(self):
        self.position_pub.publish(self.pos)
        if self.key_code == Key.KEY_RIGHT:
            self.pos.x += 1.0
        elif self.key_code == Key.KEY_LEFT:
            self.pos.x -= 1.0
        elif self.key_code == Key.KEY_UP:
            self.pos.y += 1.0
        elif self.key_code == Key.KEY_DOWN:
            self.pos.y -= 1.0
        self.key_code = -1


def main():
    rclpy.init()
    try:
        rclpy.spin(KeyboardManager())
    except (ExternalShutdownException, KeyboardInterrupt):
        pass
    finally:
        rclpy.try_shutdown()


if __name__ == "__main__":
    main()
