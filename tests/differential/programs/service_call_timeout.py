"""A synchronous call to a service nobody serves: rclpy 9 raises TimeoutError once its timeout
passes (it used to return None)."""

import rclpy
from rclpy.node import Node
from std_srvs.srv import Trigger


def main():
    rclpy.init()
    node = Node('lonely')
    client = node.create_client(Trigger, 'nobody_serves_this')
    print('ready:', client.wait_for_service(timeout_sec=0.1))
    try:
        print('call returned:', client.call(Trigger.Request(), timeout_sec=0.2))
    except Exception as exc:
        print('call raised:', type(exc).__name__, repr(str(exc)))
    rclpy.shutdown()


if __name__ == '__main__':
    main()
