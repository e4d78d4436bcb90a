"""mimic: turtlesim's tutorial node that makes one turtle copy another's moves.

``turtle_mimic`` turns each ``input/pose`` into an ``output/cmd_vel`` with the pose's linear and
angular velocity; a launch remaps the two onto two turtles.
"""

from __future__ import annotations

from node_runtime.bus import Node
from node_runtime.msgs import Twist
from node_runtime.msgs.generated.turtlesim import Pose
from server.packages.turtlesim.turtlesim_node import TOPIC_DEPTH


class MimicNode(Node):
    def __init__(self) -> None:
        super().__init__("turtle_mimic")
        self.twist_pub = self.create_publisher(Twist, "output/cmd_vel", TOPIC_DEPTH, hand_over=True)
        self.create_subscription(Pose, "input/pose", self.on_pose, TOPIC_DEPTH, read_only=True)

    def on_pose(self, pose: Pose) -> None:
        twist = Twist()
        twist.linear.x, twist.angular.z = pose.linear_velocity, pose.angular_velocity
        self.twist_pub.publish(twist)
