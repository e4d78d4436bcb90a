"""A callback that raises: the exception leaves rclpy.spin, the tutorial's try/except for Ctrl-C
does not catch it, its finally still shuts down, and Python prints it and exits with 1."""

import rclpy
from rclpy.node import Node
from std_msgs.msg import String


class Fragile(Node):
    def __init__(self):
        super().__init__('fragile')
        self.count = 0
        self.create_timer(0.05, self.tick)

    def tick(self):
        self.count += 1
        self.get_logger().info('tick %d' % self.count)
        if self.count == 3:
            raise RuntimeError('sensor unplugged')


def main(args=None):
    rclpy.init(args=args)
    node = Fragile()
    node.create_publisher(String, 'unused', 10)
    try:
        rclpy.spin(node)
    except KeyboardInterrupt:
        pass
    finally:
        print('ok before shutdown:', rclpy.ok())
        node.destroy_node()
        rclpy.try_shutdown()


if __name__ == '__main__':
    main()
