"""rclpy.event_handler: matched events as subscriptions come and go, and incompatible QoS seen
from both ends, with the QoS events a program may also ask for accepted."""

import rclpy
from rclpy.event_handler import (
    PublisherEventCallbacks,
    QoSPublisherMatchedInfo,
    QoSSubscriptionMatchedInfo,
    SubscriptionEventCallbacks,
)
from rclpy.node import Node
from rclpy.qos import QoSPolicyKind, QoSProfile, ReliabilityPolicy
from std_msgs.msg import String


def spin_until(node, condition):
    for _ in range(200):
        if condition():
            return True
        rclpy.spin_once(node, timeout_sec=0.05)
    return condition()


def fields(info):
    return (info.total_count, info.total_count_change, info.current_count, info.current_count_change)


def main():
    rclpy.init()
    node = Node('events')
    pub_matched, sub_matched = [], []
    pub = node.create_publisher(
        String, 'chatter', 10,
        event_callbacks=PublisherEventCallbacks(
            matched=pub_matched.append, liveliness=print, deadline=print))
    print('no subscription yet:', spin_until(node, lambda: pub_matched) and fields(pub_matched[-1]))
    sub = node.create_subscription(
        String, 'chatter', lambda msg: None, 10,
        event_callbacks=SubscriptionEventCallbacks(
            matched=sub_matched.append, message_lost=print, liveliness=print))
    spin_until(node, lambda: pub_matched and sub_matched)
    print('publisher matched:', type(pub_matched[-1]).__name__, fields(pub_matched[-1]))
    print('subscription matched:', type(sub_matched[-1]).__name__, fields(sub_matched[-1]))
    print('info types:', QoSPublisherMatchedInfo is QoSSubscriptionMatchedInfo or 'distinct')
    second = node.create_subscription(String, 'chatter', lambda msg: None, 10)
    spin_until(node, lambda: fields(pub_matched[-1])[2] == 2)
    print('second subscription:', fields(pub_matched[-1]))
    node.destroy_subscription(second)
    node.destroy_subscription(sub)
    spin_until(node, lambda: fields(pub_matched[-1])[2] == 0)
    print('both gone:', fields(pub_matched[-1]))

    offered, requested = [], []
    node.create_publisher(
        String, 'qos', QoSProfile(depth=5, reliability=ReliabilityPolicy.BEST_EFFORT),
        event_callbacks=PublisherEventCallbacks(incompatible_qos=offered.append))
    node.create_subscription(
        String, 'qos', lambda msg: None, QoSProfile(depth=5, reliability=ReliabilityPolicy.RELIABLE),
        event_callbacks=SubscriptionEventCallbacks(incompatible_qos=requested.append))
    spin_until(node, lambda: offered and requested)
    for name, events in (('offered', offered), ('requested', requested)):
        event = events[-1]
        print(name, event.total_count, event.total_count_change,
              QoSPolicyKind(event.last_policy_kind).name)
    node.destroy_node()
    rclpy.shutdown()


if __name__ == '__main__':
    main()
