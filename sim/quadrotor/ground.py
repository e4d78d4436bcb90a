"""Contact with the flat ground z = 0, applied after each integration step.

A projection model rather than a contact force: penetration is removed, downward
velocity is killed (a plastic landing), Coulomb friction slows horizontal motion by
the normal force, and a drone that thrust cannot lift settles level on its legs.
QuadrotorSim applies it to its state (apply); QuadrotorBatch to its drones in contact, either
one at a time through apply or, for many, through apply_columns, which does apply's operations
in apply's order on numpy columns and calls math's functions per drone where apply calls them.
So a drone touches down, slides and settles bit for bit the same alone or in a batch.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from sim.quadrotor.dynamics import QUAT, RATES, ROTORS, VEL, Vector
from sim.quadrotor.params import QuadrotorParams
from sim.quadrotor.rotation import quat_yaw
from sim.types import FloatArray

BoolArray = npt.NDArray[np.bool_]
_VX, _VY, _VZ, _WX, _WY, _WZ, _PZ = (
    VEL.start,
    VEL.start + 1,
    VEL.start + 2,
    *range(RATES.start, RATES.stop),
    8,
)
_QW, _QX, _QY, _QZ = range(QUAT.start, QUAT.stop)


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

    def apply_columns(self, s: FloatArray) -> BoolArray:
        """apply for every column of s, a block of a batch state (rows as in sim.quadrotor.dynamics)
        whose drones all touch the ground (z <= 0), in place; returns which of them rest."""
        s[_PZ] = 0.0
        vz = s[_VZ]
        vz[vz < 0.0] = 0.0  # max(vz, 0.0), keeping -0.0 as max does
        r = s[ROTORS]
        qx, qy = s[_QX], s[_QY]
        body_z_up = 1.0 - 2.0 * (qx * qx + qy * qy)
        lift = self._thrust_per_mass * (r[0] * r[0] + r[1] * r[1] + r[2] * r[2] + r[3] * r[3]) * body_z_up
        normal_acc = self._g - lift
        resting: BoolArray = ~(normal_acc <= 0.0)
        if resting.all():
            self._rest_columns(s, normal_acc)
        elif resting.any():
            rest = s[:, resting]
            self._rest_columns(rest, normal_acc[resting])
            s[:, resting] = rest
        return resting

    def _rest_columns(self, s: FloatArray, normal_acc: FloatArray) -> None:
        """The resting part of apply, _friction and _settle_level, column by column: math's hypot,
        atan2, cos and sin per drone, the rest as numpy passes in apply's order."""
        s[_VZ] = 0.0
        vx, vy = s[_VX], s[_VY]
        q = s[QUAT]
        qw, qx, qy, qz = q
        speed = np.array(list(map(math.hypot, vx.tolist(), vy.tolist())))
        yaw_y, yaw_x = 2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz)  # quat_yaw's atan2
        half_yaw = (0.5 * np.array(list(map(math.atan2, yaw_y.tolist(), yaw_x.tolist())))).tolist()
        lw, lz = np.array(list(map(math.cos, half_yaw))), np.array(list(map(math.sin, half_yaw)))
        slow_by = self._friction_dv * normal_acc
        stop = speed <= slow_by
        if stop.all():
            vx[:] = 0.0
            vy[:] = 0.0
        else:
            slide = ~stop
            scale = 1.0 - slow_by[slide] / speed[slide]
            vx[slide] *= scale
            vy[slide] *= scale
            vx[stop] = 0.0
            vy[stop] = 0.0
        flip = qw * lw + qz * lz < 0.0
        if flip.any():
            lw[flip] = -lw[flip]
            lz[flip] = -lz[flip]
        # q + k (level - q) with level = (lw, 0, 0, lz): for x and y that is exactly x - k x.
        level = np.zeros_like(q)
        level[0], level[3] = lw, lz
        level -= q
        level *= self._settle
        q += level
        squares = q * q
        q *= 1.0 / np.sqrt(squares[0] + squares[1] + squares[2] + squares[3])
        s[_WX] = 0.0
        s[_WY] = 0.0
        s[_WZ] *= 1.0 - self._settle
