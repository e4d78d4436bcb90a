"""The synchronous client: Client.call from the main thread while another thread spins."""

import contextlib
import sys
import threading

import rclpy
from example_interfaces.srv import AddTwoInts
from rclpy.executors import ExternalShutdownException


def spin_until_shutdown(node):
    with contextlib.suppress(ExternalShutdownException):
        rclpy.spin(node)


def main():
    with rclpy.init():
        node = rclpy.create_node("minimal_client_sync")
        cli = node.create_client(AddTwoInts, "add_two_ints")
        spinner = threading.Thread(target=spin_until_shutdown, args=(node,), daemon=True)
        spinner.start()
        while not cli.wait_for_service(timeout_sec=1.0):
            node.get_logger().info("service not available, waiting again...")
        a, b = int(sys.argv[1]), int(sys.argv[2])
        response = cli.call(AddTwoInts.Request(a=a, b=b))
        node.get_logger().info(f"Result of add_two_ints: for {a} + {b} = {response.sum}")
    spinner.join(timeout=5)


if __name__ == "__main__":
    main()
