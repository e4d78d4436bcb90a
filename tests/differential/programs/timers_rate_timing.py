"""A timer at 20 Hz and a Rate at 10 Hz (rate.sleep() in a thread while the node spins), each
measured over a second; a cancelled timer stays quiet and a reset one ticks again."""

import threading
import time

import rclpy
from rclpy.node import Node


class Ticker(Node):
    def __init__(self):
        super().__init__('ticker')
        self.ticks = []
        self.timer = self.create_timer(0.05, self.tick)

    def tick(self):
        self.ticks.append(time.monotonic())


def main():
    rclpy.init()
    node = Ticker()
    rate = node.create_rate(10)
    loops = []

    def loop():
        while len(loops) < 11:
            loops.append(time.monotonic())
            rate.sleep()

    looper = threading.Thread(target=loop)
    looper.start()
    while len(node.ticks) < 21 or looper.is_alive():
        rclpy.spin_once(node, timeout_sec=0.1)
    looper.join()
    print('measured timer rate: %.2f Hz' % (20 / (node.ticks[20] - node.ticks[0])))
    print('measured rate loop: %.2f Hz' % (10 / (loops[10] - loops[0])))

    node.timer.cancel()
    count = len(node.ticks)
    end = time.monotonic() + 0.2
    while time.monotonic() < end:
        rclpy.spin_once(node, timeout_sec=0.05)
    print('ticks while cancelled:', len(node.ticks) - count, node.timer.is_canceled())
    node.timer.reset()
    while len(node.ticks) < count + 2:
        rclpy.spin_once(node, timeout_sec=0.1)
    print('ticking again:', not node.timer.is_canceled())
    node.destroy_node()
    rclpy.shutdown()


if __name__ == '__main__':
    main()
