"""A Rate made with node.create_rate is given back with node.destroy_rate, as rclpy's Node has it."""

import threading

import rclpy
from rclpy.node import Node


def main():
    rclpy.init()
    node = Node('rated')
    rate = node.create_rate(50)
    spinner = threading.Thread(target=rclpy.spin, args=(node,), daemon=True)
    spinner.start()
    for _ in range(3):
        rate.sleep()
    print('slept three times')
    print('destroyed:', node.destroy_rate(rate))
    rclpy.shutdown()
    spinner.join()


if __name__ == '__main__':
    main()
