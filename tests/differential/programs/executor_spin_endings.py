"""How spinning ends: rclpy.shutdown() inside a callback ends rclpy.spin quietly; an exception
in a callback comes out of spin on the single- and the multi-threaded executor; async subscription
callbacks on a MultiThreadedExecutor's threads."""

import rclpy
from rclpy.callback_groups import ReentrantCallbackGroup
from rclpy.executors import MultiThreadedExecutor, SingleThreadedExecutor
from rclpy.node import Node
from std_msgs.msg import Int32


class Ticker(Node):
    def __init__(self, name, action):
        super().__init__(name)
        self.count = 0
        self.action = action
        self.timer = self.create_timer(0.02, self.tick)

    def tick(self):
        self.count += 1
        if self.count == 3:
            self.action(self)


class Boom(Exception):
    pass


def boom(node):
    raise Boom('tick %d of %s' % (node.count, node.get_name()))


def main():
    rclpy.init()
    for executor_type in (SingleThreadedExecutor, MultiThreadedExecutor):
        executor = executor_type()
        node = Ticker('raiser_' + executor_type.__name__[:5].lower(), boom)
        executor.add_node(node)
        try:
            executor.spin()
        except Boom as exc:
            print(executor_type.__name__, 'spin raised:', exc)
        node.timer.cancel()

    heard = []
    listener = Node('async_listener')
    group = ReentrantCallbackGroup()

    async def on_number(msg):
        heard.append(msg.data)

    listener.create_subscription(Int32, 'numbers', on_number, 10, callback_group=group)
    talker = Node('talker')
    pub = talker.create_publisher(Int32, 'numbers', 10)
    executor = MultiThreadedExecutor()
    executor.add_node(listener)
    executor.add_node(talker)
    while pub.get_subscription_count() == 0:
        executor.spin_once(timeout_sec=0.05)
    for i in range(5):
        pub.publish(Int32(data=i))
    while len(heard) < 5:
        executor.spin_once(timeout_sec=0.5)
    print('async callbacks on threads heard:', sorted(heard))
    executor.shutdown()

    node = Ticker('quitter', lambda n: rclpy.shutdown())
    rclpy.spin(node)
    print('rclpy.shutdown() in a callback ended rclpy.spin after', node.count, 'ticks; ok:', rclpy.ok())


if __name__ == '__main__':
    main()
