"""Continuous-time rigid-body + rotor dynamics and one classic RK4 step.

The state is a flat list of 17 floats, in this order:
position (3, world, m), velocity (3, world, m/s), attitude quaternion (w, x, y, z),
body rates (3, body, rad/s), rotor speeds (4, rad/s).
Plain floats rather than numpy arrays: at this size numpy's per-call overhead
dominates and the step runs several times faster without it.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from sim.quadrotor.params import QuadrotorParams

STATE_SIZE = 17
Vector = list[float]
NO_NOISE = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)


class RigidBodyModel:
    """Per-vehicle constants the derivative needs, pre-combined once."""

    __slots__ = (
        "drag_per_mass",
        "g",
        "gyro_x",
        "gyro_y",
        "gyro_z",
        "motor_rate",
        "pitch_gain",
        "roll_gain",
        "thrust_per_mass",
        "yaw_gain",
    )

    def __init__(self, p: QuadrotorParams) -> None:
        ix, iy, iz = p.inertia_kg_m2
        k_t, k_q, arm = p.thrust_coeff_n_per_rad_s2, p.torque_coeff_nm_per_rad_s2, p.arm_length_m
        self.g = p.gravity_m_s2
        self.thrust_per_mass = k_t / p.mass_kg
        # Angular acceleration per unit of signed sum of squared rotor speeds.
        self.roll_gain = arm * k_t / ix
        self.pitch_gain = arm * k_t / iy
        self.yaw_gain = k_q / iz
        # Euler's equation: I w_dot = M - w x (I w), divided through by I.
        on = 1.0 if p.gyroscopic_enabled else 0.0
        self.gyro_x = on * (iy - iz) / ix
        self.gyro_y = on * (iz - ix) / iy
        self.gyro_z = on * (ix - iy) / iz
        self.drag_per_mass = p.drag_coeff_n_per_m_s2 / p.mass_kg
        self.motor_rate = 1.0 / p.motor_time_constant_s


def derivative(
    s: Sequence[float], rotor_cmd: Sequence[float], m: RigidBodyModel, noise: Sequence[float]
) -> Vector:
    """d(state)/dt for constant rotor-speed commands and constant process noise.

    noise is (linear accel x, y, z in m/s^2, angular accel x, y, z in rad/s^2).
    """
    _, _, _, vx, vy, vz, qw, qx, qy, qz, wx, wy, wz, r1, r2, r3, r4 = s
    s1, s2, s3, s4 = r1 * r1, r2 * r2, r3 * r3, r4 * r4
    thrust_acc = m.thrust_per_mass * (s1 + s2 + s3 + s4)
    # Body z axis in the world frame: third column of R(q).
    bx = 2.0 * (qx * qz + qw * qy)
    by = 2.0 * (qy * qz - qw * qx)
    bz = 1.0 - 2.0 * (qx * qx + qy * qy)
    drag = m.drag_per_mass * math.sqrt(vx * vx + vy * vy + vz * vz)
    c1, c2, c3, c4 = rotor_cmd
    rate = m.motor_rate
    return [
        vx,
        vy,
        vz,
        thrust_acc * bx - drag * vx + noise[0],
        thrust_acc * by - drag * vy + noise[1],
        thrust_acc * bz - drag * vz - m.g + noise[2],
        # q_dot = 0.5 * q (x) (0, w), Hamilton product.
        -0.5 * (qx * wx + qy * wy + qz * wz),
        0.5 * (qw * wx + qy * wz - qz * wy),
        0.5 * (qw * wy + qz * wx - qx * wz),
        0.5 * (qw * wz + qx * wy - qy * wx),
        m.roll_gain * (s1 + s2 - s3 - s4) + m.gyro_x * wy * wz + noise[3],
        m.pitch_gain * (s2 + s3 - s1 - s4) + m.gyro_y * wz * wx + noise[4],
        m.yaw_gain * (s2 + s4 - s1 - s3) + m.gyro_z * wx * wy + noise[5],
        rate * (c1 - r1),
        rate * (c2 - r2),
        rate * (c3 - r3),
        rate * (c4 - r4),
    ]


def rk4_step(
    s: Sequence[float], rotor_cmd: Sequence[float], m: RigidBodyModel, noise: Sequence[float], h: float
) -> Vector:
    """One classic fourth-order Runge-Kutta step of length h (s), inputs held constant."""
    half = 0.5 * h
    k1 = derivative(s, rotor_cmd, m, noise)
    k2 = derivative([a + half * b for a, b in zip(s, k1, strict=True)], rotor_cmd, m, noise)
    k3 = derivative([a + half * b for a, b in zip(s, k2, strict=True)], rotor_cmd, m, noise)
    k4 = derivative([a + h * b for a, b in zip(s, k3, strict=True)], rotor_cmd, m, noise)
    sixth = h / 6.0
    return [a + sixth * (b + 2.0 * (c + d) + e) for a, b, c, d, e in zip(s, k1, k2, k3, k4, strict=True)]


def normalize_quaternion(s: Vector) -> None:
    """Rescale the attitude quaternion (indices 6-9) to unit length, in place."""
    qw, qx, qy, qz = s[6], s[7], s[8], s[9]
    inv = 1.0 / math.sqrt(qw * qw + qx * qx + qy * qy + qz * qz)
    s[6], s[7], s[8], s[9] = qw * inv, qx * inv, qy * inv, qz * inv
