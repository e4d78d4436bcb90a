#!/usr/bin/env python
import rclpy
from rclpy.node import Node
from std_msgs.msg import Bool
from keyboard_msgs.msg import Key
from rclpy.executors import ExternalShutdownException

# Create a class which we will use to take keyboard commands and convert them to an abort message
class KeyboardManager(Node):
    # On node initialization
    def __init__(self):
        super().__init__('KeyboardManagerNode')
        self.abort_pub = self.create_publisher(Bool, '/abort_takeoff', 1)
        self.key_sub = self.create_subscription(Key, '/keydown', self.get_key, 1)
        self.abort = Bool()
        self.key_code = -1
        # process key codes at 10Hz
        self.timer = self.create_timer(1/10, self.process_key_code)

    # Callback for the keyboard sub
    def get_key(self, msg):
       self.key_code = msg.code

    def process_key_code(self):
       if self.key_code == Key.KEY_A:
          # "a" key was pressed
          print("a key was pressed!")
          self.abort.data = True
       self.abort_pub.publish(self.abort)
       # Reset the code
       if self.key_code != -1:
          self.key_code = -1

# Main function
if __name__ == '__main__':
    rclpy.init()
    try:
        rclpy.spin(KeyboardManager())
    except (ExternalShutdownException, KeyboardInterrupt):
        pass
    finally:
        rclpy.try_shutdown()
