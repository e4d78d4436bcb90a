"""TransformStamped messages for the tf2 tests, built as a broadcaster builds them."""

from __future__ import annotations

import math

from geometry_msgs.msg import TransformStamped

NS_PER_S = 1_000_000_000


def yaw(angle_rad: float) -> tuple[float, float, float, float]:
    """A rotation about z, as (x, y, z, w)."""
    return 0.0, 0.0, math.sin(angle_rad / 2), math.cos(angle_rad / 2)


def stamped(
    parent: str,
    child: str,
    t_s: float,
    xyz: tuple[float, float, float] = (0.0, 0.0, 0.0),
    q: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 1.0),
) -> TransformStamped:
    out = TransformStamped()
    out.header.frame_id, out.child_frame_id = parent, child
    out.header.stamp.sec, out.header.stamp.nanosec = divmod(round(t_s * NS_PER_S), NS_PER_S)
    tr, r = out.transform.translation, out.transform.rotation
    tr.x, tr.y, tr.z = xyz
    r.x, r.y, r.z, r.w = q
    return out


def xyz(t: TransformStamped) -> tuple[float, float, float]:
    tr = t.transform.translation
    return tr.x, tr.y, tr.z


def quat(t: TransformStamped) -> tuple[float, float, float, float]:
    r = t.transform.rotation
    return r.x, r.y, r.z, r.w
