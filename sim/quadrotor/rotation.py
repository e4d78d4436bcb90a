"""Quaternion (scalar first: w, x, y, z) and Euler 'sxyz' conversions.

'sxyz' means static axes, roll about x, then pitch about y, then yaw about z:
R = Rz(yaw) @ Ry(pitch) @ Rx(roll), the convention of the lab's visualiser.
"""

from __future__ import annotations

import math

import numpy as np

from sim.types import FloatArray, FloatsLike

Quaternion = tuple[float, float, float, float]


def euler_sxyz_to_quat(roll_rad: float, pitch_rad: float, yaw_rad: float) -> Quaternion:
    """Unit quaternion (w, x, y, z) of R = Rz(yaw) Ry(pitch) Rx(roll)."""
    cr, sr = math.cos(0.5 * roll_rad), math.sin(0.5 * roll_rad)
    cp, sp = math.cos(0.5 * pitch_rad), math.sin(0.5 * pitch_rad)
    cy, sy = math.cos(0.5 * yaw_rad), math.sin(0.5 * yaw_rad)
    return (
        cy * cp * cr + sy * sp * sr,
        cy * cp * sr - sy * sp * cr,
        cy * sp * cr + sy * cp * sr,
        sy * cp * cr - cy * sp * sr,
    )


def quat_to_euler_sxyz(q: FloatsLike) -> tuple[float, float, float]:
    """(roll, pitch, yaw) in rad of a unit quaternion (w, x, y, z); pitch in [-pi/2, pi/2]."""
    w, x, y, z = (float(c) for c in q)
    roll = math.atan2(2.0 * (w * x + y * z), 1.0 - 2.0 * (x * x + y * y))
    # Clamped because rounding can push the sine a hair past +-1 at gimbal lock.
    pitch = math.asin(max(-1.0, min(1.0, 2.0 * (w * y - z * x))))
    yaw = math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))
    return roll, pitch, yaw


def quat_yaw(w: float, x: float, y: float, z: float) -> float:
    """Yaw (rad) of a unit quaternion, the 'sxyz' third angle."""
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


def quat_to_matrix(q: FloatsLike) -> FloatArray:
    """3x3 rotation matrix taking body-frame vectors to the world frame."""
    w, x, y, z = (float(c) for c in q)
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )


def wrap_angle(angle_rad: float) -> float:
    """Angle wrapped into [-pi, pi)."""
    return (angle_rad + math.pi) % (2.0 * math.pi) - math.pi
