"""ros2/examples' action server with an async execute callback, on a MultiThreadedExecutor in a
thread of its own (as if in another terminal), and a client that awaits send_goal_async,
get_result_async and cancel_goal_async inside a task of its executor: feedback in order, a result,
a goal cancelled midway, and a goal rejected by an async goal callback."""

import threading
import time

import rclpy
from action_msgs.msg import GoalStatus
from example_interfaces.action import Fibonacci
from rclpy.action import ActionClient, ActionServer, CancelResponse, GoalResponse
from rclpy.callback_groups import ReentrantCallbackGroup
from rclpy.executors import MultiThreadedExecutor, SingleThreadedExecutor
from rclpy.node import Node
from rclpy.task import Future


class MinimalActionServer(Node):
    def __init__(self):
        super().__init__('minimal_action_server')
        self._action_server = ActionServer(
            self, Fibonacci, 'fibonacci', execute_callback=self.execute_callback,
            callback_group=ReentrantCallbackGroup(), goal_callback=self.goal_callback,
            cancel_callback=self.cancel_callback)

    async def goal_callback(self, goal_request):
        self.get_logger().info('Received goal request: order %d' % goal_request.order)
        return GoalResponse.REJECT if goal_request.order < 0 else GoalResponse.ACCEPT

    def cancel_callback(self, goal_handle):
        self.get_logger().info('Received cancel request')
        return CancelResponse.ACCEPT

    async def execute_callback(self, goal_handle):
        feedback_msg = Fibonacci.Feedback()
        feedback_msg.sequence = [0, 1]
        for i in range(1, goal_handle.request.order):
            # A long goal waits after its first step for the client's cancel: else whether a second
            # feedback beats the cancel is a race, which ROS 2's rclpy itself prints either way.
            end = time.monotonic() + 10.0
            while i > 1 and goal_handle.request.order > 10 and not goal_handle.is_cancel_requested:
                if time.monotonic() > end:
                    break
                time.sleep(0.01)
            time.sleep(0.2)  # the work of a step; the client's lines come in between
            if goal_handle.is_cancel_requested:
                goal_handle.canceled()
                self.get_logger().info('Goal canceled')
                return Fibonacci.Result(sequence=feedback_msg.sequence)
            feedback_msg.sequence.append(feedback_msg.sequence[i] + feedback_msg.sequence[i - 1])
            self.get_logger().info('Publishing feedback: {0}'.format(list(feedback_msg.sequence)))
            goal_handle.publish_feedback(feedback_msg)
        goal_handle.succeed()
        self.get_logger().info('Returning result: {0}'.format(list(feedback_msg.sequence)))
        return Fibonacci.Result(sequence=feedback_msg.sequence)


def main():
    rclpy.init()
    server = MinimalActionServer()
    server_executor = MultiThreadedExecutor(num_threads=2)
    server_executor.add_node(server)
    spinner = threading.Thread(target=server_executor.spin)
    spinner.start()

    node = Node('minimal_action_client')
    client = ActionClient(node, Fibonacci, 'fibonacci')
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    log = node.get_logger()

    async def run_goals():
        client.wait_for_server()
        seen = []
        goal_handle = await client.send_goal_async(
            Fibonacci.Goal(order=4), feedback_callback=lambda fb: seen.append(list(fb.feedback.sequence)))
        log.info('Goal accepted: %s' % goal_handle.accepted)
        response = await goal_handle.get_result_async()
        log.info('Result: %s, succeeded: %s' % (
            list(response.result.sequence), response.status == GoalStatus.STATUS_SUCCEEDED))
        log.info('Feedback seen: %s' % seen)

        first_feedback = Future()

        def on_feedback(fb):
            if not first_feedback.done():
                first_feedback.set_result(list(fb.feedback.sequence))

        goal_handle = await client.send_goal_async(Fibonacci.Goal(order=30), feedback_callback=on_feedback)
        log.info('Second goal accepted: %s, first feedback %s' % (goal_handle.accepted, await first_feedback))
        cancel = await goal_handle.cancel_goal_async()
        log.info('Goals canceling: %d' % len(cancel.goals_canceling))
        response = await goal_handle.get_result_async()
        log.info('Cancelled: %s, status %d' % (
            response.status == GoalStatus.STATUS_CANCELED, goal_handle.status))

        goal_handle = await client.send_goal_async(Fibonacci.Goal(order=-1))
        log.info('Negative goal accepted: %s' % goal_handle.accepted)
        return 'all goals done'

    task = executor.create_task(run_goals)
    executor.spin_until_future_complete(task, timeout_sec=20.0)
    print('task:', task.result())
    server_executor.shutdown()
    spinner.join()
    executor.shutdown()
    rclpy.shutdown()


if __name__ == '__main__':
    main()
