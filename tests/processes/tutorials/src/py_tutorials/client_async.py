"""The asynchronous client: call_async, then spin until the future completes."""

import sys

import rclpy
from example_interfaces.srv import AddTwoInts
from rclpy.node import Node


class MinimalClientAsync(Node):
    def __init__(self):
        super().__init__("minimal_client_async")
        self.cli = self.create_client(AddTwoInts, "add_two_ints")
        while not self.cli.wait_for_service(timeout_sec=1.0):
            self.get_logger().info("service not available, waiting again...")
        self.req = AddTwoInts.Request()

    def send_request(self, a, b):
        self.req.a = a
        self.req.b = b
        return self.cli.call_async(self.req)


def main():
    with rclpy.init():
        client = MinimalClientAsync()
        a, b = int(sys.argv[1]), int(sys.argv[2])
        future = client.send_request(a, b)
        rclpy.spin_until_future_complete(client, future)
        client.get_logger().info(f"Result of add_two_ints: for {a} + {b} = {future.result().sum}")


if __name__ == "__main__":
    main()
