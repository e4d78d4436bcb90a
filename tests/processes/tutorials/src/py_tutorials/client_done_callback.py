"""A client that learns the result in a done callback of the future. The executor runs the done
callback as a task of its own after the step that completed the future, as rclpy's does, so the
client spins until the callback has run, not merely until the future is done."""

import sys

import rclpy
from example_interfaces.srv import AddTwoInts
from rclpy.node import Node


class CallbackClient(Node):
    def __init__(self, a, b):
        super().__init__("minimal_client_callback")
        self.cli = self.create_client(AddTwoInts, "add_two_ints")
        while not self.cli.wait_for_service(timeout_sec=1.0):
            self.get_logger().info("service not available, waiting again...")
        self.a, self.b = a, b
        self.answered = False
        self.future = self.cli.call_async(AddTwoInts.Request(a=a, b=b))
        self.future.add_done_callback(self.on_response)

    def on_response(self, future):
        self.get_logger().info(f"Result of add_two_ints: for {self.a} + {self.b} = {future.result().sum}")
        self.answered = True


def main():
    with rclpy.init():
        node = CallbackClient(int(sys.argv[1]), int(sys.argv[2]))
        while rclpy.ok() and not node.answered:
            rclpy.spin_once(node, timeout_sec=0.5)


if __name__ == "__main__":
    main()
