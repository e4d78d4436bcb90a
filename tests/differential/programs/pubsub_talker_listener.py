"""The tutorial's talker and listener, as two nodes in one executor: five messages, in order."""

import rclpy
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from std_msgs.msg import String


class MinimalPublisher(Node):
    def __init__(self):
        super().__init__('minimal_publisher')
        self.publisher_ = self.create_publisher(String, 'topic', 10)
        self.i = 0

    def publish_one(self):
        msg = String()
        msg.data = 'Hello World: %d' % self.i
        self.publisher_.publish(msg)
        self.get_logger().info('Publishing: "%s"' % msg.data)
        self.i += 1


class MinimalSubscriber(Node):
    def __init__(self):
        super().__init__('minimal_subscriber')
        self.subscription = self.create_subscription(String, 'topic', self.listener_callback, 10)
        self.heard = []

    def listener_callback(self, msg):
        self.get_logger().info('I heard: "%s"' % msg.data)
        self.heard.append(msg.data)


def main():
    rclpy.init()
    publisher = MinimalPublisher()
    subscriber = MinimalSubscriber()
    executor = SingleThreadedExecutor()
    executor.add_node(publisher)
    executor.add_node(subscriber)
    while publisher.publisher_.get_subscription_count() == 0:
        executor.spin_once(timeout_sec=0.05)
    print('subscribers:', publisher.publisher_.get_subscription_count())
    print('publishers:', subscriber.count_publishers('topic'), 'subscribers:', publisher.count_subscribers('/topic'))
    for _ in range(5):
        publisher.publish_one()
        while len(subscriber.heard) < publisher.i:
            executor.spin_once(timeout_sec=1.0)
    print('heard in order:', subscriber.heard)
    print('topic name:', publisher.publisher_.topic_name, subscriber.subscription.topic_name)
    executor.shutdown()
    publisher.destroy_node()
    subscriber.destroy_node()
    rclpy.shutdown()
    print('ok after shutdown:', rclpy.ok())


if __name__ == '__main__':
    main()
