"""rclpy.utilities, a raw subscription's CDR bytes with rclpy.serialization, a callback that
takes the message info too, and rclpy.wait_for_message."""

import sys
import threading

import rclpy
from rclpy.node import Node
from rclpy.serialization import deserialize_message, serialize_message
from rclpy.utilities import get_default_context, ok, remove_ros_args, timeout_sec_to_nsec
from rclpy.wait_for_message import wait_for_message
from std_msgs.msg import Int32, String


def main():
    argv = ['prog', 'mine', '--ros-args', '-r', '__node:=renamed', '--', 'also_mine']
    print('remove_ros_args:', remove_ros_args(argv))
    print('timeouts:', timeout_sec_to_nsec(None), timeout_sec_to_nsec(-2), timeout_sec_to_nsec(1.5))
    print('ok before init:', ok())
    rclpy.init(args=sys.argv)
    print('default context:', get_default_context() is get_default_context(), ok(),
          get_default_context().ok())
    node = Node('raw_listener')
    got = []
    node.create_subscription(String, 'words', got.append, 10, raw=True)
    pub = node.create_publisher(String, 'words', 10)
    pub.publish(String(data='hello'))
    while not got:
        rclpy.spin_once(node, timeout_sec=1.0)
    raw = got[0]
    print('raw:', type(raw).__name__, raw[:4].hex(), deserialize_message(raw, String).data)
    print('round trip:', deserialize_message(serialize_message(Int32(data=-7)), Int32).data)
    pub.publish(serialize_message(String(data='from bytes')))
    while len(got) < 2:
        rclpy.spin_once(node, timeout_sec=1.0)
    print('published bytes:', deserialize_message(got[1], String).data)
    infos = []
    node.create_subscription(String, 'words', lambda msg, info: infos.append((msg, info)), 10)
    pub.publish(String(data='with info'))
    while not infos:
        rclpy.spin_once(node, timeout_sec=1.0)
    msg, info = infos[0]
    print('message info:', msg.data, type(info).__name__, sorted(info),
          info['received_timestamp'] >= info['source_timestamp'] > 0)

    print('nothing yet:', wait_for_message(Int32, node, 'numbers', time_to_wait=0.2))
    numbers = node.create_publisher(Int32, 'numbers', 10)
    stop = threading.Event()

    def send():
        while not stop.wait(0.05):
            numbers.publish(Int32(data=42))

    sender = threading.Thread(target=send)
    sender.start()
    success, msg = wait_for_message(Int32, node, 'numbers', time_to_wait=5.0)
    stop.set()
    sender.join()
    print('waited:', success, msg.data)
    node.destroy_node()
    rclpy.shutdown()
    print('ok after shutdown:', ok())


if __name__ == '__main__':
    main()
