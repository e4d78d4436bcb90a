"""An action server whose execute_callback is async def (it awaits a service call for every
step), and a client that sends its goal and awaits the goal handle and the result inside a task
made with executor.create_task, as ros2/examples' async clients do."""

import rclpy
from action_msgs.msg import GoalStatus
from example_interfaces.action import Fibonacci
from rclpy.action import ActionClient, ActionServer
from rclpy.callback_groups import ReentrantCallbackGroup
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from std_srvs.srv import Trigger


class SlowFibonacci(Node):
    def __init__(self):
        super().__init__('slow_fibonacci')
        self.steps = 0
        self.create_service(Trigger, 'step', self.step)
        group = ReentrantCallbackGroup()
        self.stepper = self.create_client(Trigger, 'step', callback_group=group)
        self._action_server = ActionServer(
            self, Fibonacci, 'fibonacci', self.execute_callback, callback_group=group)

    def step(self, request, response):
        self.steps += 1
        response.success = True
        response.message = 'step %d' % self.steps
        return response

    async def execute_callback(self, goal_handle):
        self.get_logger().info('Executing goal of order %d' % goal_handle.request.order)
        sequence = [0, 1]
        for i in range(1, goal_handle.request.order):
            answer = await self.stepper.call_async(Trigger.Request())
            sequence.append(sequence[i] + sequence[i - 1])
            self.get_logger().info('%s: %s' % (answer.message, sequence))
            goal_handle.publish_feedback(Fibonacci.Feedback(sequence=sequence))
        goal_handle.succeed()
        return Fibonacci.Result(sequence=sequence)


class Client(Node):
    def __init__(self):
        super().__init__('fibonacci_client')
        self._action_client = ActionClient(self, Fibonacci, 'fibonacci')
        self.feedback = []

    async def run(self, order):
        goal_handle = await self._action_client.send_goal_async(
            Fibonacci.Goal(order=order), feedback_callback=lambda fb: self.feedback.append(len(fb.feedback.sequence)))
        self.get_logger().info('Goal accepted: %s' % goal_handle.accepted)
        result = await goal_handle.get_result_async()
        self.get_logger().info('Result: %s' % list(result.result.sequence))
        return result.status


def main():
    rclpy.init()
    server = SlowFibonacci()
    client = Client()
    executor = SingleThreadedExecutor()
    executor.add_node(server)
    executor.add_node(client)
    while not client._action_client.server_is_ready():
        executor.spin_once(timeout_sec=0.05)
    task = executor.create_task(client.run(5))
    executor.spin_until_future_complete(task, timeout_sec=10.0)
    print('status succeeded:', task.result() == GoalStatus.STATUS_SUCCEEDED)
    while len(client.feedback) < 4:
        executor.spin_once(timeout_sec=1.0)
    print('feedback lengths:', client.feedback)
    rclpy.shutdown()


if __name__ == '__main__':
    main()
