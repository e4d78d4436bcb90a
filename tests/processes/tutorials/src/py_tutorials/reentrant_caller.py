"""Executors and callback groups: a timer calls a service synchronously from its callback, which
completes because the MultiThreadedExecutor runs the reentrant group on other threads."""

import rclpy
from example_interfaces.srv import AddTwoInts
from rclpy.callback_groups import ReentrantCallbackGroup
from rclpy.executors import ExternalShutdownException, MultiThreadedExecutor
from rclpy.node import Node


class ReentrantCaller(Node):
    def __init__(self):
        super().__init__("reentrant_caller")
        group = ReentrantCallbackGroup()
        self.cli = self.create_client(AddTwoInts, "add_two_ints", callback_group=group)
        self.timer = self.create_timer(0.2, self.tick, callback_group=group)
        self.count = 0

    def tick(self):
        if not self.cli.service_is_ready():
            return
        self.count += 1
        response = self.cli.call(AddTwoInts.Request(a=self.count, b=100))
        self.get_logger().info(f"call {self.count} from the timer: {self.count} + 100 = {response.sum}")


def main(args=None):
    try:
        with rclpy.init(args=args):
            executor = MultiThreadedExecutor(num_threads=4)
            executor.add_node(ReentrantCaller())
            executor.spin()
    except (KeyboardInterrupt, ExternalShutdownException):
        pass


if __name__ == "__main__":
    main()
