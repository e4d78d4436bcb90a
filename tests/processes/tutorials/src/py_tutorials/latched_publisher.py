"""A transient-local publisher: it publishes once and keeps the sample for subscribers to come."""

import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from rclpy.qos import QoSDurabilityPolicy, QoSProfile
from std_msgs.msg import String


class LatchedPublisher(Node):
    def __init__(self):
        super().__init__("latched_publisher")
        qos = QoSProfile(depth=1, durability=QoSDurabilityPolicy.TRANSIENT_LOCAL)
        self.publisher_ = self.create_publisher(String, "map_name", qos)
        self.publisher_.publish(String(data="the lab floor"))
        self.get_logger().info('Published once: "the lab floor"')


def main(args=None):
    try:
        with rclpy.init(args=args):
            rclpy.spin(LatchedPublisher())
    except (KeyboardInterrupt, ExternalShutdownException):
        pass


if __name__ == "__main__":
    main()
