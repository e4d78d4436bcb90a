"""The "Monitoring for parameter changes" tutorial: a ParameterEventHandler calls back when a
parameter of this node and of another node changes, and for every event when asked."""

import rclpy
import rclpy.node
from rclpy.executors import SingleThreadedExecutor
from rclpy.parameter import Parameter
from rclpy.parameter_event_handler import ParameterEventHandler


class SampleNodeWithParameters(rclpy.node.Node):
    def __init__(self):
        super().__init__('node_with_parameters')
        self.declare_parameter('an_int_param', 0)
        self.handler = ParameterEventHandler(self)
        self.callback_handle = self.handler.add_parameter_callback(
            parameter_name='an_int_param',
            node_name='node_with_parameters',
            callback=self.callback,
        )
        self.remote = self.handler.add_parameter_callback(
            parameter_name='a_string_param',
            node_name='/other_node',
            callback=self.callback,
        )
        self.events = []
        self.event_handle = self.handler.add_parameter_event_callback(
            callback=lambda event: self.events.append((event.node, [p.name for p in event.changed_parameters])))

    def callback(self, p: rclpy.parameter.Parameter) -> None:
        self.get_logger().info(f'Received an update to parameter: {p.name}: {rclpy.parameter.parameter_value_to_python(p.value)}')


def main():
    rclpy.init()
    node = SampleNodeWithParameters()
    other = rclpy.node.Node('other_node')
    other.declare_parameter('a_string_param', 'hello')
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    executor.add_node(other)
    sub_count = lambda: node.count_subscribers('/parameter_events')
    while sub_count() == 0:
        executor.spin_once(timeout_sec=0.05)
    for _ in range(5):
        executor.spin_once(timeout_sec=0.05)
    node.set_parameters([Parameter('an_int_param', value=42)])
    other.set_parameters([Parameter('a_string_param', value='world')])
    while len([e for e in node.events if e[1]]) < 2:
        executor.spin_once(timeout_sec=0.5)
    print('changed events:', sorted(e for e in node.events if e[1]))
    node.handler.remove_parameter_callback(node.callback_handle)
    node.set_parameters([Parameter('an_int_param', value=7)])
    while len([e for e in node.events if e[1]]) < 3:
        executor.spin_once(timeout_sec=0.5)
    print('after remove: no more callbacks for an_int_param')
    rclpy.shutdown()


if __name__ == '__main__':
    main()
