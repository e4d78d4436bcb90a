"""Using parameters in a class: a parameter read on a timer, reset by the node itself, and a
set-parameters callback that refuses what it does not allow, with its reason."""

import rclpy
import rclpy.node
from rcl_interfaces.msg import ParameterDescriptor, SetParametersResult
from rclpy.executors import ExternalShutdownException


class MinimalParam(rclpy.node.Node):
    def __init__(self):
        super().__init__("minimal_param_node")
        descriptor = ParameterDescriptor(description="This parameter is mine!")
        self.declare_parameter("my_parameter", "world", descriptor)
        self.add_on_set_parameters_callback(self.on_set)
        self.timer = self.create_timer(0.2, self.timer_callback)

    def on_set(self, params):
        for param in params:
            if param.name == "my_parameter" and not param.value:
                return SetParametersResult(successful=False, reason="my_parameter must not be empty")
        return SetParametersResult(successful=True)

    def timer_callback(self):
        my_param = self.get_parameter("my_parameter").get_parameter_value().string_value
        self.get_logger().info(f"Hello {my_param}!")
        refused = self.set_parameters([rclpy.Parameter("my_parameter", rclpy.Parameter.Type.STRING, "")])[0]
        self.get_logger().info(f"Setting it empty: {refused.successful}, {refused.reason}")
        self.set_parameters([rclpy.Parameter("my_parameter", rclpy.Parameter.Type.STRING, "world")])


def main(args=None):
    try:
        with rclpy.init(args=args):
            rclpy.spin(MinimalParam())
    except (KeyboardInterrupt, ExternalShutdownException):
        pass


if __name__ == "__main__":
    main()
