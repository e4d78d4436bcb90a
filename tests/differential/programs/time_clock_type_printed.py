"""rclpy's Time, Duration and clocks as programs/time_and_duration.py uses them, printing the clock
types as rclpy prints them (ClockType.ROS_TIME, not a number)."""

import rclpy
from builtin_interfaces.msg import Duration as DurationMsg
from rclpy.clock import Clock, ClockType
from rclpy.duration import Duration
from rclpy.node import Node
from rclpy.time import Time


def main():
    rclpy.init()
    node = Node('clocked')
    t = Time(seconds=10, nanoseconds=500_000_000)
    d = Duration(seconds=1, nanoseconds=250_000_000)
    print('time:', t.nanoseconds, t.seconds_nanoseconds(), t.clock_type)
    print('plus:', (t + d).nanoseconds, 'minus:', (t - d).nanoseconds, 'between:', (t - Time(seconds=4)).nanoseconds)
    print('compare:', t > Time(seconds=10), d < Duration(seconds=2), d == Duration(nanoseconds=1_250_000_000))
    msg = t.to_msg()
    print('msg:', msg.sec, msg.nanosec, Time.from_msg(msg).nanoseconds == t.nanoseconds, Time.from_msg(msg).clock_type)
    dmsg = d.to_msg()
    print('duration msg:', type(dmsg) is DurationMsg, dmsg.sec, dmsg.nanosec, Duration.from_msg(dmsg).nanoseconds)
    print('scaled:', (d * 2).nanoseconds, 'seconds:', Duration(seconds=1.5).nanoseconds)
    for attempt in (lambda: t + t, lambda: t - Time(seconds=1, clock_type=ClockType.STEADY_TIME),
                    lambda: t < 5):
        try:
            attempt()
            print('no exception')
        except Exception as exc:
            print('raised', type(exc).__name__)
    clock = node.get_clock()
    print('node clock:', clock.clock_type, type(clock.now()).__name__, clock.now().nanoseconds > 0)
    steady = Clock(clock_type=ClockType.STEADY_TIME)
    before = steady.now()
    print('steady goes on:', steady.now() >= before, before.clock_type)
    node.destroy_node()
    rclpy.shutdown()


if __name__ == '__main__':
    main()
