"""rclpy's callback groups: accepted so a node file runs; the lab's executors run a node's callbacks
one at a time (rclpy's default, mutually exclusive per node)."""


class CallbackGroup:
    pass


class MutuallyExclusiveCallbackGroup(CallbackGroup):
    pass


class ReentrantCallbackGroup(CallbackGroup):
    pass
