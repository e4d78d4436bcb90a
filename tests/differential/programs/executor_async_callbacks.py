"""async def callbacks: a timer's that awaits a service call three times (its client in a
callback group of its own, as rclpy needs: the timer's group stays busy while its coroutine
waits), a service's own async callback, and a subscription's; each await resumes in order."""

import rclpy
from rclpy.callback_groups import MutuallyExclusiveCallbackGroup
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from std_msgs.msg import String
from std_srvs.srv import SetBool


class Switch(Node):
    def __init__(self):
        super().__init__('switch')
        self.on = False
        self.create_service(SetBool, 'switch', self.toggle)

    async def toggle(self, request, response):
        self.get_logger().info('switching to %s' % request.data)
        response.success = request.data != self.on
        response.message = 'was %s' % self.on
        self.on = request.data
        return response


class Caller(Node):
    def __init__(self):
        super().__init__('caller')
        self.client = self.create_client(
            SetBool, 'switch', callback_group=MutuallyExclusiveCallbackGroup())
        self.pub = self.create_publisher(String, 'said', 10)
        self.create_subscription(String, 'said', self.heard, 10)
        self.heard_lines = []
        self.timer = self.create_timer(0.05, self.on_timer)
        self.finished = False

    async def on_timer(self):
        self.timer.cancel()
        self.get_logger().info('timer fired, calling')
        for value in (True, True, False):
            response = await self.client.call_async(SetBool.Request(data=value))
            self.get_logger().info('got success=%s message=%s' % (response.success, response.message))
            self.pub.publish(String(data='after %s' % value))
        self.finished = True

    async def heard(self, msg):
        self.heard_lines.append(msg.data)


def main():
    rclpy.init()
    switch = Switch()
    caller = Caller()
    executor = SingleThreadedExecutor()
    executor.add_node(switch)
    executor.add_node(caller)
    while caller.pub.get_subscription_count() == 0 or not caller.client.service_is_ready():
        executor.spin_once(timeout_sec=0.05)
    while not caller.finished or len(caller.heard_lines) < 3:
        executor.spin_once(timeout_sec=1.0)
    print('heard:', caller.heard_lines)
    rclpy.shutdown()


if __name__ == '__main__':
    main()
