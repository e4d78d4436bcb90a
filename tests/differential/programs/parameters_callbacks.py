"""Parameters as "Using parameters in a class" and "Monitoring for parameter changes" teach:
declare with defaults and descriptors, read, set (accepted and rejected by a callback), the
exceptions for undeclared, re-declared and wrongly typed parameters, and a post-set callback."""

import rclpy
from rcl_interfaces.msg import ParameterDescriptor, SetParametersResult
from rclpy.exceptions import (
    InvalidParameterTypeException,
    ParameterAlreadyDeclaredException,
    ParameterNotDeclaredException,
)
from rclpy.node import Node
from rclpy.parameter import Parameter


class MinimalParam(Node):
    def __init__(self):
        super().__init__('minimal_param_node')
        descriptor = ParameterDescriptor(description='This parameter is mine!')
        self.declare_parameter('my_parameter', 'world', descriptor)
        self.declare_parameters(
            namespace='',
            parameters=[('speed', 1.5), ('count', 3), ('enabled', True), ('names', ['a', 'b'])],
        )
        self.add_on_set_parameters_callback(self.check)
        self.add_post_set_parameters_callback(self.after)

    def check(self, params):
        for param in params:
            self.get_logger().info('validating %s = %r' % (param.name, param.value))
            if param.name == 'speed' and param.value < 0.0:
                return SetParametersResult(successful=False, reason='speed must be >= 0')
        return SetParametersResult(successful=True)

    def after(self, params):
        self.get_logger().info('set: %s' % ', '.join('%s=%r' % (p.name, p.value) for p in params))


def main():
    rclpy.init()
    node = MinimalParam()
    my_param = node.get_parameter('my_parameter').get_parameter_value().string_value
    node.get_logger().info('Hello %s!' % my_param)
    for name in ('speed', 'count', 'enabled', 'names'):
        param = node.get_parameter(name)
        print(name, repr(param.value), param.type_.name)
    print('descriptor:', node.describe_parameter('my_parameter').description)
    print('has:', node.has_parameter('speed'), node.has_parameter('nope'))
    results = node.set_parameters([Parameter('speed', Parameter.Type.DOUBLE, 2.5)])
    print('set speed 2.5:', results[0].successful, repr(results[0].reason))
    results = node.set_parameters([Parameter('speed', Parameter.Type.DOUBLE, -1.0)])
    print('set speed -1.0:', results[0].successful, repr(results[0].reason))
    print('speed now:', node.get_parameter('speed').value)
    result = node.set_parameters_atomically([Parameter('count', value=7), Parameter('my_parameter', value='earth')])
    print('atomically:', result.successful, node.get_parameter('count').value, node.get_parameter('my_parameter').value)
    for attempt in (
        lambda: node.get_parameter('undeclared'),
        lambda: node.declare_parameter('speed', 9.0),
        lambda: node.set_parameters([Parameter('count', value='seven')]),
        lambda: node.set_parameters([Parameter('undeclared', value=1)]),
    ):
        try:
            result = attempt()
            print('no exception:', [r.successful for r in result] if isinstance(result, list) else result)
        except (ParameterNotDeclaredException, ParameterAlreadyDeclaredException, InvalidParameterTypeException) as exc:
            print('raised', type(exc).__name__)
    print('names:', sorted(n for n in node.list_parameters([], 1).names if n in ('count', 'enabled', 'speed')))
    print('undeclared default:', node.get_parameter_or('other', Parameter('other', value=4)).value)
    node.destroy_node()
    rclpy.shutdown()


if __name__ == '__main__':
    main()
