"""rclpy.service_introspection: a service and a client that publish their calls' events on
<service>/_service_event, with the contents, then only the metadata, then nothing."""

import rclpy
from rclpy.node import Node
from rclpy.qos import qos_profile_system_default
from rclpy.service_introspection import ServiceIntrospectionState
from std_srvs.srv import SetBool


def main():
    rclpy.init()
    node = Node('introspected')
    service = node.create_service(SetBool, 'switch', lambda req, res: SetBool.Response(success=req.data, message='done'))
    client = node.create_client(SetBool, 'switch')
    events = []
    node.create_subscription(SetBool.Event, '/switch/_service_event', events.append, 10)
    print('event type:', SetBool.Event.__name__)
    for state in (ServiceIntrospectionState.CONTENTS, ServiceIntrospectionState.METADATA,
                  ServiceIntrospectionState.OFF):
        service.configure_introspection(node.get_clock(), qos_profile_system_default, state)
        client.configure_introspection(node.get_clock(), qos_profile_system_default, state)
        while node.count_publishers('/switch/_service_event') != (0 if state == ServiceIntrospectionState.OFF else 2):
            rclpy.spin_once(node, timeout_sec=0.05)
        events.clear()
        client.wait_for_service(5.0)
        future = client.call_async(SetBool.Request(data=True))
        rclpy.spin_until_future_complete(node, future, timeout_sec=5.0)
        expected = 0 if state == ServiceIntrospectionState.OFF else 4
        for _ in range(100):
            if len(events) >= expected and (expected or _ > 10):
                break
            rclpy.spin_once(node, timeout_sec=0.05)
        print(state.name, 'response:', future.result().success, future.result().message)
        for event in sorted(events, key=lambda e: e.info.event_type):
            print(' ', event.info.event_type, event.info.sequence_number,
                  [r.data for r in event.request], [(r.success, r.message) for r in event.response])
    node.destroy_node()
    rclpy.shutdown()


if __name__ == '__main__':
    main()
