"""Contact with the flat ground z = 0, applied after each integration step.

A projection model rather than a contact force: penetration is removed, downward
velocity is killed (a plastic landing), Coulomb friction slows horizontal motion by
the normal force, and a drone that thrust cannot lift settles level on its legs.
"""

from __future__ import annotations

import math

from sim.quadrotor.dynamics import Vector
from sim.quadrotor.params import QuadrotorParams
from sim.quadrotor.rotation import quat_yaw


class GroundContact:
    """Applies the ground constraint to a state vector (see sim.quadrotor.dynamics)."""

    def __init__(self, p: QuadrotorParams, dt_s: float) -> None:
        self._g = p.gravity_m_s2
        self._thrust_per_mass = p.thrust_coeff_n_per_rad_s2 / p.mass_kg
        self._friction_dv = p.ground_friction_coeff * dt_s
        # Fraction of the remaining tilt and spin removed per step while resting.
        self._settle = 1.0 - math.exp(-dt_s / p.ground_level_time_constant_s)

    def apply(self, s: Vector) -> tuple[bool, bool]:
        """Constrain s in place; returns (in_contact, resting)."""
        if s[2] > 0.0:
            return False, False
        s[2] = 0.0
        s[5] = max(s[5], 0.0)
        r1, r2, r3, r4 = s[13], s[14], s[15], s[16]
        qx, qy = s[7], s[8]
        body_z_up = 1.0 - 2.0 * (qx * qx + qy * qy)  # world-z component of the body z axis
        lift = self._thrust_per_mass * (r1 * r1 + r2 * r2 + r3 * r3 + r4 * r4) * body_z_up
        normal_acc = self._g - lift
        if normal_acc <= 0.0:
            return True, False  # thrust carries the weight: lifting off, no friction
        s[5] = 0.0
        self._friction(s, normal_acc)
        self._settle_level(s)
        return True, True

    def _friction(self, s: Vector, normal_acc: float) -> None:
        speed = math.hypot(s[3], s[4])
        slow_by = self._friction_dv * normal_acc
        if speed <= slow_by:
            s[3] = s[4] = 0.0
        else:
            scale = 1.0 - slow_by / speed
            s[3] *= scale
            s[4] *= scale

    def _settle_level(self, s: Vector) -> None:
        """Blend attitude toward the same heading held level; damp the body rates."""
        qw, qx, qy, qz = s[6], s[7], s[8], s[9]
        half_yaw = 0.5 * quat_yaw(qw, qx, qy, qz)
        lw, lz = math.cos(half_yaw), math.sin(half_yaw)
        if qw * lw + qz * lz < 0.0:  # same rotation, other hemisphere: blend the short way
            lw, lz = -lw, -lz
        k = self._settle
        qw, qx, qy, qz = qw + k * (lw - qw), qx - k * qx, qy - k * qy, qz + k * (lz - qz)
        inv = 1.0 / math.sqrt(qw * qw + qx * qx + qy * qy + qz * qz)
        s[6], s[7], s[8], s[9] = qw * inv, qx * inv, qy * inv, qz * inv
        keep = 1.0 - k
        # Roll and pitch rates stop against the legs; yaw spin decays with the same constant.
        s[10], s[11], s[12] = 0.0, 0.0, s[12] * keep
