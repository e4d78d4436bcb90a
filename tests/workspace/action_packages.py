"""Our own versions of ROS 2's "Writing an action server and client (Python)" nodes, laid out as
ros2/demos lays out ``action_tutorials_py`` below ``src/``: an ament_python package with
console_scripts, using ``action_tutorials_interfaces``' Fibonacci."""

from __future__ import annotations

from pathlib import Path

from .tutorial_packages import python_package

PACKAGE = "action_tutorials_py"
STEP_S = 0.2  # the tutorial's server sleeps a second a step; ours is quicker, the lines the same

# As the tutorial's server: default goal and cancel callbacks, one feedback a step.
SERVER = f"""
import time

import rclpy
from rclpy.action import ActionServer
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node

from action_tutorials_interfaces.action import Fibonacci


class FibonacciActionServer(Node):

    def __init__(self):
        super().__init__('fibonacci_action_server')
        self._action_server = ActionServer(self, Fibonacci, 'fibonacci', self.execute_callback)

    def execute_callback(self, goal_handle):
        self.get_logger().info('Executing goal...')
        feedback = Fibonacci.Feedback()
        feedback.partial_sequence = [0, 1]
        for i in range(1, goal_handle.request.order):
            seq = feedback.partial_sequence
            seq.append(seq[i] + seq[i - 1])
            self.get_logger().info('Feedback: {{0}}'.format(seq))
            goal_handle.publish_feedback(feedback)
            time.sleep({STEP_S})
        goal_handle.succeed()
        result = Fibonacci.Result()
        result.sequence = feedback.partial_sequence
        return result


def main(args=None):
    try:
        with rclpy.init(args=args):
            rclpy.spin(FibonacciActionServer())
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
"""

# As the tutorial's client, with the order as a parameter (10, as the tutorial sends).
CLIENT = """
import rclpy
from rclpy.action import ActionClient
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node

from action_tutorials_interfaces.action import Fibonacci


class FibonacciActionClient(Node):

    def __init__(self):
        super().__init__('fibonacci_action_client')
        self.declare_parameter('order', 10)
        self._action_client = ActionClient(self, Fibonacci, 'fibonacci')

    def send_goal(self):
        goal = Fibonacci.Goal()
        goal.order = self.get_parameter('order').value
        self._action_client.wait_for_server()
        self._send_goal_future = self._action_client.send_goal_async(
            goal, feedback_callback=self.feedback_callback)
        self._send_goal_future.add_done_callback(self.goal_response_callback)

    def goal_response_callback(self, future):
        goal_handle = future.result()
        if not goal_handle.accepted:
            self.get_logger().info('Goal rejected :(')
            rclpy.shutdown()
            return
        self.get_logger().info('Goal accepted :)')
        self._get_result_future = goal_handle.get_result_async()
        self._get_result_future.add_done_callback(self.get_result_callback)

    def get_result_callback(self, future):
        result = future.result().result
        self.get_logger().info('Result: {0}'.format(result.sequence))
        rclpy.shutdown()

    def feedback_callback(self, feedback_msg):
        self.get_logger().info('Received feedback: {0}'.format(feedback_msg.feedback.partial_sequence))


def main(args=None):
    try:
        with rclpy.init(args=args):
            client = FibonacciActionClient()
            client.send_goal()
            rclpy.spin(client)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
"""

# A server that refuses goals whose sequence would overflow int32 and lets goals be cancelled,
# its callbacks in a reentrant group on a MultiThreadedExecutor, as rclpy's examples do.
CANCELABLE_SERVER = f"""
import time

import rclpy
from rclpy.action import ActionServer, CancelResponse, GoalResponse
from rclpy.callback_groups import ReentrantCallbackGroup
from rclpy.executors import ExternalShutdownException, MultiThreadedExecutor
from rclpy.node import Node

from action_tutorials_interfaces.action import Fibonacci

LARGEST_ORDER = 46  # Fibonacci(47) does not fit an int32


class CancelableFibonacciServer(Node):

    def __init__(self):
        super().__init__('cancelable_fibonacci_server')
        self._server = ActionServer(
            self, Fibonacci, 'fibonacci', self.execute_callback,
            callback_group=ReentrantCallbackGroup(),
            goal_callback=self.goal_callback, cancel_callback=self.cancel_callback)

    def goal_callback(self, goal_request):
        if goal_request.order > LARGEST_ORDER:
            self.get_logger().info('Rejecting goal of order {{0}}'.format(goal_request.order))
            return GoalResponse.REJECT
        self.get_logger().info('Accepting goal of order {{0}}'.format(goal_request.order))
        return GoalResponse.ACCEPT

    def cancel_callback(self, goal_handle):
        self.get_logger().info('Received cancel request')
        return CancelResponse.ACCEPT

    def execute_callback(self, goal_handle):
        feedback = Fibonacci.Feedback(partial_sequence=[0, 1])
        for i in range(1, goal_handle.request.order):
            if goal_handle.is_cancel_requested:
                goal_handle.canceled()
                self.get_logger().info('Goal canceled')
                return Fibonacci.Result(sequence=feedback.partial_sequence)
            feedback.partial_sequence.append(feedback.partial_sequence[i] + feedback.partial_sequence[i - 1])
            goal_handle.publish_feedback(feedback)
            time.sleep({STEP_S})
        goal_handle.succeed()
        return Fibonacci.Result(sequence=feedback.partial_sequence)


def main(args=None):
    try:
        with rclpy.init(args=args):
            rclpy.spin(CancelableFibonacciServer(), executor=MultiThreadedExecutor())
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
"""

# A client that cancels its goal once the first feedback came, and says what became of it.
CANCELING_CLIENT = """
import rclpy
from action_msgs.msg import GoalStatus
from rclpy.action import ActionClient
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node

from action_tutorials_interfaces.action import Fibonacci


class CancelingClient(Node):

    def __init__(self):
        super().__init__('canceling_client')
        self._client = ActionClient(self, Fibonacci, 'fibonacci')
        self._goal_handle = None
        self._cancel_sent = False

    def send_goal(self):
        self._client.wait_for_server()
        future = self._client.send_goal_async(Fibonacci.Goal(order=40), feedback_callback=self.on_feedback)
        future.add_done_callback(self.on_goal_response)

    def on_goal_response(self, future):
        self._goal_handle = future.result()
        self.get_logger().info('Goal accepted: {0}'.format(self._goal_handle.accepted))
        self._goal_handle.get_result_async().add_done_callback(self.on_result)

    def on_feedback(self, feedback_msg):
        if self._goal_handle is not None and not self._cancel_sent:
            self._cancel_sent = True
            self._goal_handle.cancel_goal_async().add_done_callback(self.on_cancel_response)

    def on_cancel_response(self, future):
        if len(future.result().goals_canceling) > 0:
            self.get_logger().info('Goal successfully canceled')
        else:
            self.get_logger().info('Goal failed to cancel')

    def on_result(self, future):
        answer = future.result()
        canceled = answer.status == GoalStatus.STATUS_CANCELED
        self.get_logger().info('Result status {0} (canceled: {1}), {2} numbers'.format(
            answer.status, canceled, len(answer.result.sequence)))
        rclpy.shutdown()


def main(args=None):
    try:
        with rclpy.init(args=args):
            node = CancelingClient()
            node.send_goal()
            rclpy.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
"""

SCRIPTS = {
    "fibonacci_action_server": SERVER,
    "fibonacci_action_client": CLIENT,
    "cancelable_fibonacci_server": CANCELABLE_SERVER,
    "canceling_client": CANCELING_CLIENT,
}


def demos_clone(ws: Path) -> None:
    """``src/demos/action_tutorials/action_tutorials_py`` as a clone of ros2/demos leaves it (abridged)."""
    folder = ws / "src" / "demos" / "action_tutorials" / PACKAGE
    python_package(folder, PACKAGE, [f"{name} = {PACKAGE}.{name}:main" for name in SCRIPTS], SCRIPTS)
