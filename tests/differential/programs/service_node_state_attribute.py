"""A service whose node keeps its own `self.state`, as students name it: rclpy's Node has no such
attribute, so the service answers as with any other name."""

import rclpy
from rclpy.node import Node
from std_srvs.srv import SetBool, Trigger


class Switch(Node):
    def __init__(self):
        super().__init__('switch')
        self.state = False
        self.srv = self.create_service(SetBool, 'set_state', self.set_state_callback)
        self.trigger = self.create_service(Trigger, 'report', self.report_callback)

    def set_state_callback(self, request, response):
        self.get_logger().info('Incoming request: data=%s' % request.data)
        response.success = request.data != self.state
        response.message = 'was %s, now %s' % (self.state, request.data)
        self.state = request.data
        return response

    def report_callback(self, request, response):
        response.success = True
        response.message = 'state is %s' % self.state
        return response


def main():
    rclpy.init()
    server = Switch()
    client_node = Node('switch_client')
    client = client_node.create_client(SetBool, 'set_state')
    report = client_node.create_client(Trigger, 'report')
    executor = rclpy.executors.SingleThreadedExecutor()
    executor.add_node(server)
    executor.add_node(client_node)
    while not (client.service_is_ready() and report.service_is_ready()):
        executor.spin_once(timeout_sec=0.1)
    print('ready:', client.service_is_ready(), report.service_is_ready())
    for value in (True, True, False):
        future = client.call_async(SetBool.Request(data=value))
        executor.spin_until_future_complete(future, timeout_sec=5.0)
        response = future.result()
        client_node.get_logger().info('Result: success=%s message=%s' % (response.success, response.message))
    future = report.call_async(Trigger.Request())
    executor.spin_until_future_complete(future, timeout_sec=5.0)
    print('report:', future.result().success, future.result().message)
    print('done:', future.done(), 'cancelled:', future.cancelled())
    rclpy.shutdown()


if __name__ == '__main__':
    main()
