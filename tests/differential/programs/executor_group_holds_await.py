"""A callback group stays busy while its coroutine callback waits: a timer that awaits a call of
a client in its own node's default group never gets the response; the same call from a client in
a ReentrantCallbackGroup does."""

import rclpy
from rclpy.callback_groups import ReentrantCallbackGroup
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from std_srvs.srv import Trigger


class Asker(Node):
    def __init__(self, name, group):
        super().__init__(name)
        self.client = self.create_client(Trigger, '/answer', callback_group=group)
        self.answers = []
        self.timer = self.create_timer(0.05, self.ask)

    async def ask(self):
        self.timer.cancel()
        self.get_logger().info('asking')
        response = await self.client.call_async(Trigger.Request())
        self.answers.append(response.message)
        self.get_logger().info('answered: %s' % response.message)


def main():
    rclpy.init()
    server = Node('answerer')
    server.create_service(Trigger, '/answer', lambda req, res: Trigger.Response(success=True, message='42'))
    stuck = Asker('same_group', None)
    free = Asker('reentrant_group', ReentrantCallbackGroup())
    executor = SingleThreadedExecutor()
    for node in (server, stuck, free):
        executor.add_node(node)
    while not free.answers:
        executor.spin_once(timeout_sec=0.1)
    for _ in range(10):
        executor.spin_once(timeout_sec=0.05)
    print('same group answers:', stuck.answers)
    print('reentrant group answers:', free.answers)
    rclpy.shutdown()


if __name__ == '__main__':
    main()
