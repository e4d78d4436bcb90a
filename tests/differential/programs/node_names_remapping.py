"""Names as ROS 2 resolves them: a namespace and remappings from --ros-args, a parameter
override, private (~) and absolute names, the graph as a node lists it, and the loggers' names
a namespace gives."""

import rclpy
from rclpy.node import Node
from std_msgs.msg import String
from std_srvs.srv import Trigger


def main():
    rclpy.init(args=['talker', '--ros-args', '-r', '__ns:=/robot', '-r', 'chatter:=talk',
                     '-p', 'speed:=2.5', '-p', 'name:=rover'])
    node = Node('talker', automatically_declare_parameters_from_overrides=True)
    print('node:', node.get_name(), node.get_namespace(), node.get_fully_qualified_name())
    pubs = [node.create_publisher(String, name, 10) for name in ('chatter', '~/status', '/absolute', 'rel/deep')]
    print('topics:', [pub.topic_name for pub in pubs])
    service = node.create_service(Trigger, 'reset', lambda req, res: res)
    print('service:', service.srv_name)
    print('parameters:', node.get_parameter('speed').value, node.get_parameter('name').value)
    other = Node('helper', namespace='tools')
    print('other:', other.get_fully_qualified_name())
    print('loggers:', node.get_logger().name, other.get_logger().name)
    node.get_logger().info('from the namespace --ros-args gave')
    other.get_logger().warning('from a namespace of its own')
    print('nodes:', sorted(n for n in node.get_node_names() if n in ('talker', 'helper')))
    topics = dict(node.get_topic_names_and_types())
    print('topics in graph:', sorted(t for t in topics if t.startswith('/robot') or t == '/absolute'))
    print('type:', topics['/robot/talk'])
    node.destroy_node()
    other.destroy_node()
    rclpy.shutdown()


if __name__ == '__main__':
    main()
