"""A transient-local subscription that joins after the publisher has published."""

import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from rclpy.qos import QoSDurabilityPolicy, QoSProfile, QoSReliabilityPolicy
from std_msgs.msg import String


class LateSubscriber(Node):
    def __init__(self):
        super().__init__("late_subscriber")
        qos = QoSProfile(
            depth=1,
            reliability=QoSReliabilityPolicy.RELIABLE,
            durability=QoSDurabilityPolicy.TRANSIENT_LOCAL,
        )
        self.create_subscription(String, "map_name", self.on_map, qos)

    def on_map(self, msg):
        self.get_logger().info(f'Late joiner got: "{msg.data}"')


def main(args=None):
    try:
        with rclpy.init(args=args):
            rclpy.spin(LateSubscriber())
    except (KeyboardInterrupt, ExternalShutdownException):
        pass


if __name__ == "__main__":
    main()
