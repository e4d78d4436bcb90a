"""The action tutorial's Fibonacci server and client in one process, the server spinning in a
thread of its own as if in another terminal: the goal accepted, every feedback in order, the
result and its status; then a goal the server rejects. Every feedback the server published before
it succeeded has reached the client when its result does."""

import threading
import time

import rclpy
from action_msgs.msg import GoalStatus
from example_interfaces.action import Fibonacci
from rclpy.action import ActionClient, ActionServer, CancelResponse, GoalResponse
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node


class FibonacciActionServer(Node):
    def __init__(self):
        super().__init__('fibonacci_action_server')
        self._action_server = ActionServer(
            self, Fibonacci, 'fibonacci', self.execute_callback,
            goal_callback=self.goal_callback, cancel_callback=self.cancel_callback)

    def goal_callback(self, goal_request):
        self.get_logger().info('Received goal request: order %d' % goal_request.order)
        return GoalResponse.REJECT if goal_request.order < 0 else GoalResponse.ACCEPT

    def cancel_callback(self, goal_handle):
        self.get_logger().info('Received cancel request')
        return CancelResponse.ACCEPT

    def execute_callback(self, goal_handle):
        self.get_logger().info('Executing goal...')
        feedback_msg = Fibonacci.Feedback()
        feedback_msg.sequence = [0, 1]
        for i in range(1, goal_handle.request.order):
            time.sleep(0.1)
            if goal_handle.is_cancel_requested:
                goal_handle.canceled()
                self.get_logger().info('Goal canceled')
                return Fibonacci.Result(sequence=feedback_msg.sequence)
            feedback_msg.sequence.append(feedback_msg.sequence[i] + feedback_msg.sequence[i - 1])
            self.get_logger().info('Feedback: {0}'.format(feedback_msg.sequence))
            goal_handle.publish_feedback(feedback_msg)
        goal_handle.succeed()
        result = Fibonacci.Result()
        result.sequence = feedback_msg.sequence
        return result


class FibonacciActionClient(Node):
    def __init__(self):
        super().__init__('fibonacci_action_client')
        self._action_client = ActionClient(self, Fibonacci, 'fibonacci')
        self.feedback = []

    def send_goal(self, order):
        goal_msg = Fibonacci.Goal()
        goal_msg.order = order
        self._action_client.wait_for_server()
        return self._action_client.send_goal_async(goal_msg, feedback_callback=self.feedback_callback)

    def feedback_callback(self, feedback_msg):
        self.feedback.append(list(feedback_msg.feedback.sequence))


def main():
    rclpy.init()
    server = FibonacciActionServer()
    client = FibonacciActionClient()
    server_executor = SingleThreadedExecutor()
    server_executor.add_node(server)
    spinner = threading.Thread(target=server_executor.spin)
    spinner.start()

    send_goal_future = client.send_goal(5)
    rclpy.spin_until_future_complete(client, send_goal_future)
    goal_handle = send_goal_future.result()
    result_future = goal_handle.get_result_async()
    rclpy.spin_until_future_complete(client, result_future)
    result = result_future.result()
    print('accepted:', goal_handle.accepted)
    print('status:', result.status == GoalStatus.STATUS_SUCCEEDED, 'result:', list(result.result.sequence))
    print('feedback:', client.feedback)

    rejected = client.send_goal(-1)
    rclpy.spin_until_future_complete(client, rejected)
    print('rejected goal accepted:', rejected.result().accepted)
    server_executor.shutdown()
    spinner.join()
    rclpy.shutdown()


if __name__ == '__main__':
    main()
