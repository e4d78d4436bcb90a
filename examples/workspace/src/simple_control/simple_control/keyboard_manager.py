#!/usr/bin/env python
import rclpy
from rclpy.node import Node
from keyboard_msgs.msg import Key
from rclpy.executors import ExternalShutdownException
from geometry_msgs.msg import Vector3
import time

# Create a class which we will use to take keyboard commands and convert them to a position
class KeyboardManager(Node):
    # On node initialization
    def __init__(self):
        super().__init__('KeyboardManagerNode')
        # Create the publisher and subscriber
        self.position_pub = self.create_publisher(Vector3, '/uav/input/position', 1)
        self.keyboard_sub = self.create_subscription(Key, '/keydown', self.get_key, 1)
        # Create the position message we are going to be sending
        self.pos = Vector3()
        # Set the drone's height to 3, start at the center
        self.pos.z = 3.0
        self.pos.x, self.pos.y = 0.0, 0.0
        # Create a variable we will use to hold the key code
        self.key_code = -1
        # Give the simulation enough time to start
        time.sleep(10)
        # Call the mainloop of our class
        self.rate = 20
        self.dt = 1.0 / self.rate
        self.timer = self.create_timer(self.dt, self.mainloop)

    # Callback for the keyboard sub
    def get_key(self, msg):
        self.key_code = msg.code

    def mainloop(self):
         # Publish the position
         self.position_pub.publish(self.pos)

         # Check if any key has been pressed
         if self.key_code == Key.KEY_RIGHT:
             self.pos.x += 1.0
         elif self.key_code == Key.KEY_LEFT:
             self.pos.x -= 1.0
         elif self.key_code == Key.KEY_UP:
             self.pos.y += 1.0
         elif self.key_code == Key.KEY_DOWN:
             self.pos.y -= 1.0

         # Reset the code
         if self.key_code != -1:
             self.key_code = -1

def main():
    rclpy.init()
    try:
        rclpy.spin(KeyboardManager())
    except (ExternalShutdownException, KeyboardInterrupt):
        pass
    finally:
        rclpy.try_shutdown()

# Main function
if __name__ == '__main__':
    main()

