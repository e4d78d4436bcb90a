"""The classes the node's create_* calls return, imported from their rclpy modules as type
annotations import them, with their properties and calls."""

import rclpy
from rclpy.client import Client
from rclpy.node import Node
from rclpy.publisher import Publisher
from rclpy.qos import QoSProfile, ReliabilityPolicy
from rclpy.service import Service
from rclpy.subscription import Subscription
from rclpy.timer import Timer, TimerInfo
from std_msgs.msg import String
from std_srvs.srv import Trigger


class Talker(Node):
    publisher_: Publisher
    timer: Timer

    def __init__(self):
        super().__init__('talker')
        self.publisher_ = self.create_publisher(String, 'chatter', 10)
        self.best_effort = self.create_publisher(
            String, 'other', QoSProfile(depth=3, reliability=ReliabilityPolicy.BEST_EFFORT))
        self.timer = self.create_timer(0.25, self.tick, autostart=False)
        self.ticks = 0

    def tick(self):
        self.ticks += 1


def main():
    rclpy.init()
    node = Talker()
    heard = []
    sub = node.create_subscription(String, 'chatter', heard.append, 5)
    server = node.create_service(Trigger, 'trigger', lambda req, res: res)
    client = node.create_client(Trigger, 'trigger')
    for name, entity, cls in (('publisher', node.publisher_, Publisher), ('subscription', sub, Subscription),
                              ('timer', node.timer, Timer), ('service', server, Service),
                              ('client', client, Client)):
        print(name, isinstance(entity, cls), type(entity).__module__, type(entity).__name__)
    print('publisher:', node.publisher_.topic_name, node.publisher_.qos_profile.depth,
          node.publisher_.qos_profile.reliability.name, node.publisher_.get_subscription_count())
    print('best effort:', node.best_effort.topic_name, node.best_effort.qos_profile.depth,
          node.best_effort.qos_profile.reliability.name, node.best_effort.get_subscription_count())
    print('subscription:', sub.topic_name, sub.qos_profile.depth, sub.raw, sub.get_publisher_count(),
          sub.msg_type.__name__)
    print('service:', server.srv_name, server.service_name, server.srv_type.__name__)
    print('client:', client.srv_name, client.srv_type.__name__, client.service_is_ready())
    timer = node.timer
    print('timer:', timer.timer_period_ns, timer.is_canceled(), timer.time_until_next_call())
    timer.reset()
    print('after reset:', timer.is_canceled(), timer.time_until_next_call() <= 250_000_000)
    timer.timer_period_ns = 100_000_000
    print('new period:', timer.timer_period_ns)
    timer.cancel()
    print('cancelled:', timer.is_canceled(), timer.time_until_next_call())
    infos = []

    def with_info(info: TimerInfo):
        infos.append(info)

    info_timer = node.create_timer(0.05, with_info)
    while not infos:
        rclpy.spin_once(node, timeout_sec=1.0)
    info = infos[0]
    print('timer info:', type(info.expected_call_time).__name__,
          info.actual_call_time.nanoseconds >= info.expected_call_time.nanoseconds)
    node.destroy_timer(info_timer)
    node.publisher_.publish(String(data='one'))
    try:
        node.publisher_.publish('not a message')
    except TypeError as exc:
        print('TypeError:', type(exc).__name__)
    while not heard:
        rclpy.spin_once(node, timeout_sec=1.0)
    print('heard:', [m.data for m in heard])
    print('destroyed:', node.destroy_subscription(sub), node.publisher_.get_subscription_count())
    node.destroy_node()
    rclpy.shutdown()


if __name__ == '__main__':
    main()
