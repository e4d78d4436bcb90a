"""The warning rclpy logs by default when a subscription asks for a QoS a publisher does not
offer (the publisher's side here; the subscription's callback shows the event came)."""

import time

import rclpy
from rclpy.event_handler import SubscriptionEventCallbacks
from rclpy.node import Node
from rclpy.qos import QoSProfile, ReliabilityPolicy
from std_msgs.msg import String


def main():
    rclpy.init()
    node = Node('qos_talker')
    node.create_publisher(String, 'chatter', QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT))
    requested = []
    node.create_subscription(
        String, 'chatter', lambda msg: None, QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE),
        event_callbacks=SubscriptionEventCallbacks(incompatible_qos=requested.append))
    while not requested:
        rclpy.spin_once(node, timeout_sec=0.1)
    end = time.monotonic() + 0.5
    while time.monotonic() < end:
        rclpy.spin_once(node, timeout_sec=0.05)
    print('subscription told:', requested[0].total_count)
    node.destroy_node()
    rclpy.shutdown()


if __name__ == '__main__':
    main()
