"""A subscriber whose callback is a lambda."""

import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from std_msgs.msg import String


class MinimalSubscriber(Node):
    def __init__(self):
        super().__init__("minimal_subscriber")
        self.subscription = self.create_subscription(
            String, "topic", lambda msg: self.get_logger().info(f'I heard: "{msg.data}"'), 10
        )


def main(args=None):
    try:
        with rclpy.init(args=args):
            rclpy.spin(MinimalSubscriber())
    except (KeyboardInterrupt, ExternalShutdownException):
        pass


if __name__ == "__main__":
    main()
