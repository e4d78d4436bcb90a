"""Rigid transforms as tf2 computes them: a translation (m) and a unit quaternion (x, y, z, w).

A ``RigidTransform`` maps points of a child frame into its parent: ``p_parent = R(q) p_child + t``.
Composition, inversion and interpolation (translation linearly, rotation by spherical linear
interpolation along the shorter arc) are plain numpy on float64.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

Vector = NDArray[np.float64]

# Quaternions closer than this (1 - |cos half-angle|) are interpolated linearly, then normalised:
# slerp's sin(theta) denominator vanishes there, and the two results agree to rounding.
_NEARLY_PARALLEL = 1e-9


def quaternion_multiply(a: Vector, b: Vector) -> Vector:
    """The Hamilton product ``a * b`` of two (x, y, z, w) quaternions: rotate by ``b``, then ``a``."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return np.array(
        [
            aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
            aw * bw - ax * bx - ay * by - az * bz,
        ]
    )


def quaternion_conjugate(q: Vector) -> Vector:
    """The inverse rotation of a unit quaternion."""
    return np.array([-q[0], -q[1], -q[2], q[3]])


def rotate(q: Vector, v: Vector) -> Vector:
    """``v`` rotated by the unit quaternion ``q``."""
    u, w = q[:3], q[3]
    twice_cross = 2.0 * np.cross(u, v)
    result: Vector = v + w * twice_cross + np.cross(u, twice_cross)
    return result


def slerp(q0: Vector, q1: Vector, ratio: float) -> Vector:
    """The rotation ``ratio`` of the way from ``q0`` to ``q1`` along the shorter great arc (0 gives
    ``q0``, 1 gives ``q1`` or its equal ``-q1``), at constant angular speed."""
    dot = float(np.dot(q0, q1) / np.sqrt(np.dot(q0, q0) * np.dot(q1, q1)))
    if dot < 0.0:  # q and -q are one rotation: go the short way round
        q1, dot = -q1, -dot
    if dot > 1.0 - _NEARLY_PARALLEL:
        mixed: Vector = (1.0 - ratio) * q0 + ratio * q1
        return mixed / np.linalg.norm(mixed)
    theta = np.arccos(dot)
    s = np.sin(theta)
    out: Vector = (np.sin((1.0 - ratio) * theta) / s) * q0 + (np.sin(ratio * theta) / s) * q1
    return out


@dataclass(frozen=True)
class RigidTransform:
    """Where a child frame is in its parent: ``translation`` (m, 3) and ``rotation`` (x, y, z, w)."""

    translation: Vector
    rotation: Vector

    @staticmethod
    def identity() -> RigidTransform:
        return RigidTransform(np.zeros(3), np.array([0.0, 0.0, 0.0, 1.0]))

    def __matmul__(self, other: RigidTransform) -> RigidTransform:
        """``a @ b``: first ``b`` (child of ``a``'s child), then ``a`` (a chain read left to right
        from the top frame down)."""
        return RigidTransform(
            self.translation + rotate(self.rotation, other.translation),
            quaternion_multiply(self.rotation, other.rotation),
        )

    def inverse(self) -> RigidTransform:
        """Where the parent frame is in the child: ``t @ t.inverse()`` is the identity."""
        back = quaternion_conjugate(self.rotation)
        return RigidTransform(-rotate(back, self.translation), back)

    def apply(self, point: Vector) -> Vector:
        """A point given in the child frame, expressed in the parent frame."""
        return self.translation + rotate(self.rotation, point)


def interpolate(a: RigidTransform, b: RigidTransform, ratio: float) -> RigidTransform:
    """The transform ``ratio`` of the way from ``a`` (0) to ``b`` (1)."""
    translation: Vector = a.translation + ratio * (b.translation - a.translation)
    return RigidTransform(translation, slerp(a.rotation, b.rotation, ratio))
