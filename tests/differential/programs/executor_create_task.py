"""executor.create_task with a coroutine that awaits a client's future, another task and a plain
Future; a task's result, its done callbacks, and a task that raises."""

import rclpy
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.task import Future
from std_srvs.srv import Trigger


def main():
    rclpy.init()
    node = Node('tasks')
    count = [0]

    def report(request, response):
        count[0] += 1
        response.success = True
        response.message = 'call %d' % count[0]
        return response

    node.create_service(Trigger, 'report', report)
    client = node.create_client(Trigger, 'report')
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    while not client.service_is_ready():
        executor.spin_once(timeout_sec=0.05)

    async def ask(label):
        response = await client.call_async(Trigger.Request())
        node.get_logger().info('%s: %s' % (label, response.message))
        return response.message

    later = Future()

    async def both():
        first = await executor.create_task(ask('first'))
        second = await ask('second')
        value = await later
        return [first, second, value]

    async def broken():
        await client.call_async(Trigger.Request())
        raise ValueError('bad value')

    task = executor.create_task(both())
    task.add_done_callback(lambda t: print('done callback:', t.result()))
    failing = executor.create_task(broken())
    print('task done before spinning:', task.done())
    executor.spin_once(timeout_sec=0.5)
    later.set_result('set by hand')
    while not task.done():
        try:
            executor.spin_until_future_complete(task, timeout_sec=5.0)
        except ValueError as exc:  # a task's exception leaves the spin that ran it
            print('spin raised:', type(exc).__name__, exc)
    print('result:', task.result(), task.done(), task.cancelled())
    print('failing:', failing.done(), type(failing.exception()).__name__, failing.exception())
    plain = executor.create_task(lambda: 'plain function')
    executor.spin_until_future_complete(plain, timeout_sec=5.0)
    print('plain:', plain.result())
    rclpy.shutdown()


if __name__ == '__main__':
    main()
