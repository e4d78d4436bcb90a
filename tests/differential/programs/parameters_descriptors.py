"""Parameter descriptors and the refusals a tutorial meets: a read-only parameter, an integer
range, a value of another type, a rejected default (InvalidParameterValueException), dynamic
typing, and undeclared parameters allowed by the node's options."""

import rclpy
from rcl_interfaces.msg import IntegerRange, ParameterDescriptor, SetParametersResult
from rclpy.exceptions import InvalidParameterValueException, ParameterImmutableException
from rclpy.node import Node
from rclpy.parameter import Parameter


def main():
    rclpy.init()
    node = Node('described')
    node.declare_parameter('frame', 'map', ParameterDescriptor(read_only=True))
    node.declare_parameter(
        'rate', 10, ParameterDescriptor(integer_range=[IntegerRange(from_value=1, to_value=50, step=1)]))
    node.declare_parameter('anything', 1, ParameterDescriptor(dynamic_typing=True))
    for param in (Parameter('frame', value='odom'), Parameter('rate', value=99), Parameter('rate', value=20),
                  Parameter('anything', value='now a string')):
        try:
            result = node.set_parameters([param])[0]
            print('set %s=%r:' % (param.name, param.value), result.successful, repr(result.reason))
        except ParameterImmutableException as exc:
            print('set %s=%r raised' % (param.name, param.value), type(exc).__name__)
    print('values:', node.get_parameter('frame').value, node.get_parameter('rate').value,
          node.get_parameter('anything').value)

    node.add_on_set_parameters_callback(
        lambda params: SetParametersResult(successful=all(p.name != 'forbidden' for p in params),
                                           reason='not that one'))
    try:
        node.declare_parameter('forbidden', 1)
    except InvalidParameterValueException as exc:
        print('declare forbidden raised', type(exc).__name__)
    print('forbidden declared:', node.has_parameter('forbidden'))

    loose = Node('loose', allow_undeclared_parameters=True,
                 automatically_declare_parameters_from_overrides=True)
    result = loose.set_parameters([Parameter('made_up', value=3.5)])[0]
    print('undeclared allowed:', result.successful, loose.get_parameter('made_up').value)
    print('unset is NOT_SET:', loose.get_parameter('never_set').type_.name)
    node.destroy_node()
    loose.destroy_node()
    rclpy.shutdown()


if __name__ == '__main__':
    main()
