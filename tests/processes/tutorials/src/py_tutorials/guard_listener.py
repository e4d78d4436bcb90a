"""A guard condition: the subscription's callback triggers it on every fifth message; the
executor then runs the guard's callback."""

import rclpy
from rclpy.executors import ExternalShutdownException, SingleThreadedExecutor
from rclpy.node import Node
from std_msgs.msg import String


class GuardListener(Node):
    def __init__(self):
        super().__init__("guard_listener")
        self.last = ""
        self.guard = self.create_guard_condition(self.on_guard)
        self.create_subscription(String, "topic", self.on_message, 10)
        self.heard = 0

    def on_message(self, msg):
        self.heard += 1
        self.last = msg.data
        if self.heard % 5 == 0:
            self.guard.trigger()

    def on_guard(self):
        self.get_logger().info(f'guard condition triggered after {self.heard} messages, last "{self.last}"')


def main(args=None):
    try:
        with rclpy.init(args=args):
            executor = SingleThreadedExecutor()
            executor.add_node(GuardListener())
            executor.spin()
    except (KeyboardInterrupt, ExternalShutdownException):
        pass


if __name__ == "__main__":
    main()
