"""The graph queries programs/node_names_remapping.py leaves out: get_node_names_and_namespaces,
get_service_names_and_types and get_publisher_names_and_types_by_node."""

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
    names = sorted(node.get_node_names_and_namespaces())
    print('nodes:', [n for n in names if n[0] in ('talker', 'helper')])
    topics = dict(node.get_topic_names_and_types())
    print('topics in graph:', sorted(t for t in topics if t.startswith('/robot') or t == '/absolute'))
    print('type:', topics['/robot/talk'])
    services = dict(node.get_service_names_and_types())
    print('service in graph:', services.get('/robot/reset'))
    print('publishers by node:', sorted(t for t, _ in node.get_publisher_names_and_types_by_node('talker', '/robot')
                                       if not t.startswith('/rosout') and t != '/parameter_events'))
    node.destroy_node()
    other.destroy_node()
    rclpy.shutdown()


if __name__ == '__main__':
    main()
