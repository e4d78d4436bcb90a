"""QoS a tutorial meets: a transient-local publisher's last messages reach a subscription made
after them (up to its depth), then what comes later; best effort and reliable endpoints, and the
profiles' fields."""

import rclpy
from rclpy.node import Node
from rclpy.qos import (DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy,
                       qos_profile_sensor_data)
from std_msgs.msg import Int32


def spin_until(node, condition):
    while not condition():
        rclpy.spin_once(node, timeout_sec=0.5)


def main():
    rclpy.init()
    node = Node('latched')
    latched = QoSProfile(depth=3, durability=DurabilityPolicy.TRANSIENT_LOCAL,
                         reliability=ReliabilityPolicy.RELIABLE, history=HistoryPolicy.KEEP_LAST)
    pub = node.create_publisher(Int32, 'map_version', latched)
    for i in range(5):
        pub.publish(Int32(data=i))
    late = []
    node.create_subscription(Int32, 'map_version', lambda m: late.append(m.data), latched)
    spin_until(node, lambda: len(late) >= 3)
    pub.publish(Int32(data=5))
    spin_until(node, lambda: len(late) >= 4)
    print('late transient-local subscription:', late)
    sensor = []
    node.create_subscription(Int32, 'scan', lambda m: sensor.append(m.data), qos_profile_sensor_data)
    fast = node.create_publisher(Int32, 'scan', qos_profile_sensor_data)
    spin_until(node, lambda: fast.get_subscription_count() == 1)
    fast.publish(Int32(data=42))
    spin_until(node, lambda: sensor)
    print('sensor data:', sensor)
    profile = qos_profile_sensor_data
    print('sensor profile:', profile.reliability.name, profile.durability.name, profile.history.name, profile.depth)
    print('latched profile:', latched.reliability.name, latched.durability.name, latched.depth)
    print('equal profiles:', QoSProfile(depth=10) == QoSProfile(depth=10), QoSProfile(depth=10) == latched)
    node.destroy_node()
    rclpy.shutdown()


if __name__ == '__main__':
    main()
