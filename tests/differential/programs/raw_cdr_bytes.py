"""raw=True subscriptions: the serialized CDR bytes of what was published, byte for byte, for
strings, numbers, arrays and nested messages (padding zeroed on the wire); and those bytes
deserialized again. (rclpy's serialize_message leaves padding as it finds it, so its bytes are
not compared.)"""

import rclpy
from geometry_msgs.msg import PoseStamped, Twist
from rclpy.node import Node
from rclpy.serialization import deserialize_message
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64MultiArray, Int32, String


def pose():
    msg = PoseStamped()
    msg.header.stamp.sec = 12
    msg.header.stamp.nanosec = 345
    msg.header.frame_id = 'map'
    msg.pose.position.x = 1.5
    msg.pose.orientation.w = 1.0
    return msg


def joints():
    msg = JointState()
    msg.name = ['shoulder', 'elbow']
    msg.position = [0.5, -1.25]
    msg.velocity = []
    msg.effort = [2.0]
    return msg


MESSAGES = [
    String(data='hello'),
    String(data=''),
    Int32(data=-7),
    Twist(),
    pose(),
    joints(),
    Float64MultiArray(data=[1.0, 2.0, 3.0]),
]


def main():
    rclpy.init()
    node = Node('raw_listener')
    for index, message in enumerate(MESSAGES):
        kind = type(message)
        got = []
        topic = 'raw_%d' % index
        node.create_subscription(kind, topic, got.append, 10, raw=True)
        pub = node.create_publisher(kind, topic, 10)
        while pub.get_subscription_count() == 0:
            rclpy.spin_once(node, timeout_sec=0.05)
        pub.publish(message)
        while not got:
            rclpy.spin_once(node, timeout_sec=1.0)
        raw = got[0]
        print(kind.__name__, type(raw).__name__, len(raw), raw.hex())
        print('  round trip:', deserialize_message(raw, kind) == message)
    node.destroy_node()
    rclpy.shutdown()


if __name__ == '__main__':
    main()
