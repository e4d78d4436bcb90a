from server.msgs import Point, Pose, PoseStamped, Quaternion, Twist, TwistStamped, Vector3

__all__ = ["Point", "Pose", "PoseStamped", "Quaternion", "Twist", "TwistStamped", "Vector3"]
