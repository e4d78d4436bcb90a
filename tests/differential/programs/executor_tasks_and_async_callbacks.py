"""Coroutines on the executor: create_task with a function and a coroutine, a task awaiting a
service client's future, spin_until_future_complete on a task, an async timer callback and an async
service callback, a Future's done callbacks run by the executor, a task that raises, and the deadlock of awaiting a
client of the group the awaiting callback holds."""

import time

import rclpy
from rclpy.callback_groups import MutuallyExclusiveCallbackGroup, ReentrantCallbackGroup
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.task import Future
from std_srvs.srv import SetBool


class Negator(Node):
    def __init__(self):
        super().__init__('negator')
        self.calls = 0
        self.srv = self.create_service(SetBool, 'negate', self.negate)

    async def negate(self, request, response):
        self.calls += 1
        self.get_logger().info('call %d: negating %s' % (self.calls, request.data))
        response.success = not request.data
        response.message = 'call %d' % self.calls
        return response


def main():
    rclpy.init()
    adder = Negator()
    node = Node('caller')
    group = ReentrantCallbackGroup()
    client = node.create_client(SetBool, 'negate', callback_group=group)
    executor = SingleThreadedExecutor()
    executor.add_node(adder)
    executor.add_node(node)
    while not client.wait_for_service(timeout_sec=1.0):
        pass

    plain = executor.create_task(lambda a, b: a * b, 6, 7)
    print('plain done before spinning:', plain.done())
    executor.spin_until_future_complete(plain, timeout_sec=5.0)
    print('plain:', plain.done(), plain.result())

    async def call(data, label):
        node.get_logger().info('calling with %s for %s' % (data, label))
        response = await client.call_async(SetBool.Request(data=data))
        node.get_logger().info('got %s (%s)' % (response.success, response.message))
        return response.success

    task = executor.create_task(call, True, 'the task')
    executor.spin_until_future_complete(task, timeout_sec=5.0)
    print('task:', task.done(), task.result())

    order = []
    future = Future(executor=executor)
    future.add_done_callback(lambda f: order.append('done callback saw %s' % f.result()))
    future.set_result('yes')
    order.append('after set_result')
    for _ in range(10):  # the callback is a task of its own, after the others already made
        executor.spin_once(timeout_sec=0.1)
    print('order:', order)

    ticks = []

    async def tick():
        response = await client.call_async(SetBool.Request(data=len(ticks) % 2 == 0))
        ticks.append(response.success)
        node.get_logger().info('tick %s %s' % (response.success, response.message))

    # A group of its own for the timer: a tick holds it until its coroutine ends, so the next tick
    # starts after the last one's response. (In the reentrant group, a tick could start while the
    # last one still awaits, and which request each sends would depend on the timing: ROS 2's rclpy
    # itself prints either.)
    timer = node.create_timer(0.05, tick, callback_group=MutuallyExclusiveCallbackGroup())
    while len(ticks) < 3:
        executor.spin_once(timeout_sec=1.0)
    timer.cancel()
    print('ticks:', ticks[:3])

    async def fails():
        await client.call_async(SetBool.Request(data=False))
        raise ValueError('the task failed')

    failing = executor.create_task(fails)
    try:
        executor.spin_until_future_complete(failing, timeout_sec=5.0)
    except ValueError as exc:
        print('raised from spinning:', type(exc).__name__, exc)
    print('failing:', failing.done(), type(failing.exception()).__name__)

    # The node's default group is mutually exclusive: a timer of it awaiting a client of it never
    # gets the response, which waits for the group the timer holds.
    stuck = []
    same_group_client = node.create_client(SetBool, 'negate')
    while not same_group_client.wait_for_service(timeout_sec=1.0):
        pass

    async def blocked():
        response = await same_group_client.call_async(SetBool.Request(data=True))
        stuck.append(response.success)

    blocking_timer = node.create_timer(0.05, blocked)
    end = time.monotonic() + 0.5
    while time.monotonic() < end:
        executor.spin_once(timeout_sec=0.1)
    blocking_timer.cancel()
    print('a response in the group its caller holds:', stuck)

    created = executor.create_future()
    print('created future:', type(created).__name__, created.done(), created.cancelled())
    created.cancel()
    print('cancelled future:', created.done(), created.cancelled())
    rclpy.shutdown()


if __name__ == '__main__':
    main()
