"""rclpy.qos_overriding_options: the read-only qos_overrides parameters a publisher and a
subscription declare, set from --ros-args; and a node's logger services changing what it logs."""

import sys

import rclpy
from rcl_interfaces.msg import LoggerLevel, SetParametersResult
from rcl_interfaces.srv import GetLoggerLevels, SetLoggerLevels
from rclpy.exceptions import ParameterImmutableException
from rclpy.node import Node
from rclpy.parameter import Parameter
from rclpy.qos import QoSProfile
from rclpy.qos_overriding_options import InvalidQosOverridesError, QoSOverridingOptions
from std_msgs.msg import String


def refuse_depth_over_20(qos):
    result = SetParametersResult(successful=qos.depth <= 20)
    if not result.successful:
        result.reason = 'depth over 20'
    return result


def call(node, client, request):
    future = client.call_async(request)
    rclpy.spin_until_future_complete(node, future, timeout_sec=5.0)
    return future.result()


def main():
    rclpy.init(args=sys.argv + ['--ros-args', '-p', 'qos_overrides./chatter.publisher.depth:=7',
                                '-p', 'qos_overrides./chatter.subscription_fast.reliability:=best_effort'])
    node = Node('overrides', enable_logger_service=True)
    pub = node.create_publisher(
        String, 'chatter', QoSProfile(depth=10),
        qos_overriding_options=QoSOverridingOptions.with_default_policies())
    sub = node.create_subscription(
        String, 'chatter', lambda msg: None, 10,
        qos_overriding_options=QoSOverridingOptions.with_default_policies(entity_id='fast'))
    print('publisher qos:', pub.qos_profile.depth, pub.qos_profile.reliability.name, pub.qos_profile.history.name)
    print('subscription qos:', sub.qos_profile.depth, sub.qos_profile.reliability.name)
    names = sorted(n for n in node.list_parameters([], 0).names if n.startswith('qos_overrides'))
    for name in names:
        print(' ', name, '=', node.get_parameter(name).value, node.describe_parameter(name).read_only)
    print('description:', node.describe_parameter(names[0]).description)
    try:
        node.set_parameters([Parameter('qos_overrides./chatter.publisher.depth', value=3)])
        print('set result:', node.get_parameter('qos_overrides./chatter.publisher.depth').value)
    except ParameterImmutableException as exc:
        print('immutable:', type(exc).__name__)
    results = node.set_parameters([Parameter('qos_overrides./chatter.publisher.depth', value=3)])
    print('set:', [r.successful for r in results])
    try:
        node.create_publisher(String, 'big', 30, qos_overriding_options=QoSOverridingOptions(
            [], callback=refuse_depth_over_20))
    except InvalidQosOverridesError as exc:
        print('refused:', exc)

    get_levels = node.create_client(GetLoggerLevels, 'overrides/get_logger_levels')
    set_levels = node.create_client(SetLoggerLevels, 'overrides/set_logger_levels')
    print('services ready:', get_levels.wait_for_service(5.0), set_levels.wait_for_service(5.0))
    response = call(node, get_levels, GetLoggerLevels.Request(names=['overrides', 'other']))
    print('levels:', [(lv.name, lv.level) for lv in response.levels])
    node.get_logger().debug('hidden debug line')
    request = SetLoggerLevels.Request(levels=[LoggerLevel(name='overrides', level=10),
                                              LoggerLevel(name='bad', level=15)])
    response = call(node, set_levels, request)
    print('set levels:', [(r.successful, r.reason) for r in response.results])
    node.get_logger().debug('shown debug line')
    response = call(node, get_levels, GetLoggerLevels.Request(names=['overrides']))
    print('levels now:', [(lv.name, lv.level) for lv in response.levels])
    node.destroy_node()
    rclpy.shutdown()


if __name__ == '__main__':
    main()
