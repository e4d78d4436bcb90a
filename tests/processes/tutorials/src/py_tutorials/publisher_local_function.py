"""A publisher without a class: rclpy.create_node and a local function as the timer's callback."""

import rclpy
from rclpy.executors import ExternalShutdownException
from std_msgs.msg import String


def main(args=None):
    try:
        with rclpy.init(args=args):
            node = rclpy.create_node("minimal_publisher")
            publisher = node.create_publisher(String, "topic", 10)
            count = [0]

            def timer_callback():
                msg = String(data=f"Hello World: {count[0]}")
                publisher.publish(msg)
                node.get_logger().info(f'Publishing: "{msg.data}"')
                count[0] += 1

            node.create_timer(0.1, timer_callback)
            rclpy.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass


if __name__ == "__main__":
    main()
