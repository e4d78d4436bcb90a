"""The order in which one pass of the executor runs what is ready: rclpy goes node by node, and
in a node timers first, then subscriptions, guard conditions, clients and services."""

import time

import rclpy
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from std_msgs.msg import String
from std_srvs.srv import Trigger


def main():
    rclpy.init()
    node = Node('ordered')
    ran = []
    pub = node.create_publisher(String, 'words', 10)
    node.create_subscription(String, 'words', lambda msg: ran.append('subscription'), 10)
    node.create_service(Trigger, 'poke', lambda req, res: (ran.append('service'), res)[1])
    client = node.create_client(Trigger, 'poke')
    guard = node.create_guard_condition(lambda: ran.append('guard condition'))
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    while pub.get_subscription_count() == 0 or not client.service_is_ready():
        executor.spin_once(timeout_sec=0.05)
    client.call_async(Trigger.Request())
    pub.publish(String(data='x'))
    guard.trigger()
    node.create_timer(0.01, lambda: ran.append('timer'))
    time.sleep(0.2)  # everything is ready before the executor looks
    for _ in range(4):
        executor.spin_once(timeout_sec=0)
    print('ran in order:', ran[:4])
    rclpy.shutdown()


if __name__ == '__main__':
    main()
