"""A custom callback group: the executor asks can_execute before it waits on an entity, calls
beginning_execution before the callback (and skips it when that says False) and
ending_execution after it."""

import rclpy
from rclpy.callback_groups import CallbackGroup
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from std_msgs.msg import String


class GatedGroup(CallbackGroup):
    """Runs one callback at a time, and none while closed."""

    def __init__(self):
        super().__init__()
        self.open = False
        self.busy = False
        self.log = []

    def can_execute(self, entity):
        return self.open and not self.busy

    def beginning_execution(self, entity):
        if not self.open or self.busy:
            return False
        self.busy = True
        self.log.append('begin ' + type(entity).__name__)
        return True

    def ending_execution(self, entity):
        self.busy = False
        self.log.append('end ' + type(entity).__name__)


def main():
    rclpy.init()
    node = Node('gated')
    group = GatedGroup()
    heard = []
    node.create_subscription(String, 'words', lambda msg: heard.append(msg.data), 10, callback_group=group)
    ticks = []
    timer = node.create_timer(0.05, lambda: ticks.append(1), callback_group=group)
    print('group of the timer is ours:', timer.callback_group is group)
    pub = node.create_publisher(String, 'words', 10)
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    while pub.get_subscription_count() == 0:
        executor.spin_once(timeout_sec=0.05)
    pub.publish(String(data='while closed'))
    for _ in range(6):
        executor.spin_once(timeout_sec=0.05)
    print('closed:', heard, len(ticks), group.log)
    group.open = True
    while not heard or not ticks:
        executor.spin_once(timeout_sec=0.5)
    timer.cancel()
    print('open:', heard, sorted(group.log)[:2], 'balanced:', group.log.count('end Subscription') == 1)
    print('every begin ended:', all(group.log[i].startswith('begin') and group.log[i + 1].startswith('end')
                                    for i in range(0, len(group.log), 2)))
    rclpy.shutdown()


if __name__ == '__main__':
    main()
