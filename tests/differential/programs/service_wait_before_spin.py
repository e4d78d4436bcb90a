"""The service tutorial's client waits for its service in its constructor; here the server is a
node of the same process that no executor spins yet: rclpy finds it in the graph at once. Also
the names a client and a service give (srv_name as written)."""

import rclpy
from rclpy.node import Node
from std_srvs.srv import SetBool


class MinimalClientAsync(Node):
    def __init__(self):
        super().__init__('minimal_client_async')
        self.cli = self.create_client(SetBool, 'set_flag')
        waits = 0
        while not self.cli.wait_for_service(timeout_sec=1.0):
            self.get_logger().info('service not available, waiting again...')
            waits += 1
            if waits == 3:
                break
        self.req = SetBool.Request()

    def send_request(self, value):
        self.req.data = value
        return self.cli.call_async(self.req)


def main():
    rclpy.init()
    server = Node('minimal_service')
    service = server.create_service(SetBool, 'set_flag', lambda req, res: SetBool.Response(success=req.data))
    client = MinimalClientAsync()
    print('names:', client.cli.srv_name, service.srv_name)
    future = client.send_request(True)
    executor = rclpy.executors.SingleThreadedExecutor()
    executor.add_node(server)
    executor.add_node(client)
    executor.spin_until_future_complete(future, timeout_sec=5.0)
    print('answered:', future.done() and future.result().success)
    rclpy.shutdown()


if __name__ == '__main__':
    main()
