"""ros2/examples' custom executor whole: a PriorityExecutor whose spin_once hands each ready
callback to a pool of threads, the high-priority node's to a pool of its own; talker, listener and
an estop node spun by its spin_once until the listener has heard enough.
(How many messages the estop node got before that is not printed: on Fast DDS its subscription may
miss the first ones while discovery goes on.)"""

from concurrent.futures import ThreadPoolExecutor
import os
import threading

import rclpy
from rclpy.executors import Executor
from rclpy.node import Node
from std_msgs.msg import String


class Talker(Node):
    def __init__(self):
        super().__init__('talker')
        self.i = 0
        self.pub = self.create_publisher(String, 'chatter', 10)
        self.timer = self.create_timer(0.1, self.timer_callback)

    def timer_callback(self):
        msg = String()
        msg.data = 'Hello World: {0}'.format(self.i)
        self.i += 1
        self.pub.publish(msg)


class Listener(Node):
    def __init__(self, done):
        super().__init__('listener')
        self.heard = []
        self.done = done
        self.sub = self.create_subscription(String, 'chatter', self.chatter_callback, 10)

    def chatter_callback(self, msg):
        self.heard.append(msg.data)
        if len(self.heard) > 3:
            return  # one more may come while the context shuts down
        where = 'a pool thread' if threading.current_thread() is not threading.main_thread() else 'the main thread'
        self.get_logger().info('I heard: [%s] on %s' % (msg.data, where))
        if len(self.heard) == 3:
            self.done.set()


class Estopper(Node):
    def __init__(self):
        super().__init__('estopper')
        self.sub = self.create_subscription(String, 'chatter', self.estop_callback, 10)
        self.heard = 0

    def estop_callback(self, msg):
        self.heard += 1


class PriorityExecutor(Executor):
    def __init__(self):
        super().__init__()
        self.high_priority_nodes = set()
        self.hp_executor = ThreadPoolExecutor(max_workers=os.cpu_count() or 4)
        self.lp_executor = ThreadPoolExecutor(max_workers=1)

    def add_high_priority_node(self, node):
        self.high_priority_nodes.add(node)
        self.add_node(node)

    def spin_once(self, timeout_sec=None):
        try:
            handler, group, node = self.wait_for_ready_callbacks(timeout_sec=timeout_sec)
        except StopIteration:
            pass
        else:
            if node in self.high_priority_nodes:
                self.hp_executor.submit(handler)
            else:
                self.lp_executor.submit(handler)


def main(args=None):
    done = threading.Event()
    with rclpy.init(args=args):
        listener = Listener(done)
        talker = Talker()
        estopper = Estopper()
        executor = PriorityExecutor()
        executor.add_high_priority_node(estopper)
        executor.add_node(listener)
        executor.add_node(talker)
        # Spun by hand until the listener has heard enough: a shutdown from another thread while
        # ROS 2's rclpy builds its wait set can fail inside rclpy itself.
        while not done.is_set():
            executor.spin_once()
        executor.lp_executor.shutdown()
        executor.hp_executor.shutdown()
    print('listener heard:', listener.heard[:3])


if __name__ == '__main__':
    main()
