"""A Future's done callbacks are tasks of its executor, run in the order they were made: after
a task awaited a client's response, the tasks the response and the task left (the client forgetting
the request, spin_until_future_complete's wake-up) run first, one per spin_once."""

import rclpy
from rclpy.callback_groups import ReentrantCallbackGroup
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.task import Future
from std_srvs.srv import SetBool


def main():
    rclpy.init()
    server = Node('server')
    server.create_service(SetBool, 'negate', lambda req, res: (setattr(res, 'success', not req.data), res)[1])
    node = Node('caller')
    client = node.create_client(SetBool, 'negate', callback_group=ReentrantCallbackGroup())
    executor = SingleThreadedExecutor()
    executor.add_node(server)
    executor.add_node(node)
    while not client.wait_for_service(timeout_sec=1.0):
        pass

    async def call():
        response = await client.call_async(SetBool.Request(data=True))
        return response.success

    task = executor.create_task(call)
    executor.spin_until_future_complete(task, timeout_sec=5.0)
    order = []
    future = Future(executor=executor)
    future.add_done_callback(lambda f: order.append('callback'))
    future.set_result(1)
    for i in range(5):
        executor.spin_once(timeout_sec=0.1)
        print(i, order)
    rclpy.shutdown()


if __name__ == '__main__':
    main()
