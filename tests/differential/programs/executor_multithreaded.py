"""MultiThreadedExecutor: two timers in a ReentrantCallbackGroup run at the same time (one waits
for the other), two in one MutuallyExclusiveCallbackGroup never do; a guard condition's
callback runs once per trigger."""

import threading

import rclpy
from rclpy.callback_groups import MutuallyExclusiveCallbackGroup, ReentrantCallbackGroup
from rclpy.executors import MultiThreadedExecutor
from rclpy.node import Node


def main():
    rclpy.init()
    node = Node('threads')
    met = threading.Event()
    seen = []

    def waiter():
        waiter_timer.cancel()
        seen.append('waiter met the other: %s' % met.wait(timeout=5.0))

    def setter():
        setter_timer.cancel()
        met.set()

    reentrant = ReentrantCallbackGroup()
    waiter_timer = node.create_timer(0.05, waiter, callback_group=reentrant)
    setter_timer = node.create_timer(0.1, setter, callback_group=reentrant)

    exclusive = MutuallyExclusiveCallbackGroup()
    running = []
    overlaps = []
    lock = threading.Lock()

    def busy():
        with lock:
            running.append(1)
            overlaps.append(len(running) > 1)
        threading.Event().wait(0.02)
        with lock:
            running.pop()

    exclusive_timers = [node.create_timer(0.01, busy, callback_group=exclusive) for _ in range(2)]
    guard_runs = []
    guard = node.create_guard_condition(lambda: guard_runs.append(1))

    executor = MultiThreadedExecutor(num_threads=4)
    executor.add_node(node)
    while not seen or len(overlaps) < 10:
        executor.spin_once(timeout_sec=0.5)
    for timer in exclusive_timers:
        timer.cancel()
    guard.trigger()
    while not guard_runs:
        executor.spin_once(timeout_sec=0.5)
    print(seen[0])
    print('exclusive callbacks overlapped:', any(overlaps))
    print('guard runs:', len(guard_runs))
    executor.shutdown()
    rclpy.shutdown()


if __name__ == '__main__':
    main()
