"""What rclpy prints of a parameter's type (Parameter.Type is an IntEnum: str() is its number, in
a refusal's reason too) and the parameters every node has (use_sim_time and
start_type_description_service)."""

import rclpy
from rclpy.node import Node
from rclpy.parameter import Parameter


def main():
    rclpy.init()
    node = Node('typed')
    node.declare_parameter('rate', 10)
    node.declare_parameter('names', ['a', 'b'])
    for name in ('rate', 'names'):
        param = node.get_parameter(name)
        print(name, param.type_, param.type_ == int(param.type_.value), param.type_.name)
    result = node.set_parameters([Parameter('rate', value=2.5)])[0]
    print('set rate=2.5:', result.successful, repr(result.reason))
    print('every parameter:', sorted(node.list_parameters([], 1).names))
    node.destroy_node()
    rclpy.shutdown()


if __name__ == '__main__':
    main()
