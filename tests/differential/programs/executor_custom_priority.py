"""A custom Executor as ros2/examples builds one: spin_once takes one ready callback from
wait_for_ready_callbacks and runs the high-priority node's first. With no timeout the wait blocks
until work is ready (it does not raise); with a timeout and nothing ready it raises
TimeoutException."""

import time

import rclpy
from rclpy.executors import Executor, ShutdownException, TimeoutException
from rclpy.node import Node
from std_msgs.msg import Int32


class PriorityExecutor(Executor):
    def __init__(self):
        super().__init__()
        self.high_priority_nodes = set()
        self.ran = []

    def add_high_priority_node(self, node):
        self.high_priority_nodes.add(node)
        self.add_node(node)

    def spin_once(self, timeout_sec=None):
        try:
            handler, group, node = self.wait_for_ready_callbacks(timeout_sec=timeout_sec)
        except ShutdownException:
            pass
        except TimeoutException:
            self.ran.append('timeout')
        else:
            self.ran.append(('high ' if node in self.high_priority_nodes else 'low ') + node.get_name())
            handler()
            if handler.exception() is not None:
                raise handler.exception()
            handler.result()


class Counter(Node):
    def __init__(self, name):
        super().__init__(name)
        self.got = []
        self.create_subscription(Int32, 'numbers', lambda msg: self.got.append(msg.data), 10)


def main():
    rclpy.init()
    high = Counter('estop')
    low = Counter('logger')
    executor = PriorityExecutor()
    executor.add_high_priority_node(high)
    executor.add_node(low)
    publisher = Node('source')
    pub = publisher.create_publisher(Int32, 'numbers', 10)
    while pub.get_subscription_count() < 2:
        time.sleep(0.01)

    executor.spin_once(timeout_sec=0.1)
    print('nothing ready:', executor.ran)
    executor.ran.clear()

    pub.publish(Int32(data=1))
    started = time.monotonic()
    executor.spin_once()
    executor.spin_once()
    # Which node's callback comes first is the order of rclpy's set of nodes (their ids' hashes):
    # it changes from run to run there, so the two are compared as a set.
    print('waited without timeout for the message:', sorted(executor.ran), 'in time:', time.monotonic() - started < 5)
    print('got:', high.got, low.got)

    ticks = []
    timer = low.create_timer(0.2, lambda: ticks.append(time.monotonic()))
    executor.ran.clear()
    started = time.monotonic()
    executor.spin_once()
    print('a timer ready after its period:', executor.ran, len(ticks), time.monotonic() - started > 0.15)
    low.destroy_timer(timer)
    rclpy.shutdown()


if __name__ == '__main__':
    main()
