"""Rigid-body and rotor dynamics and one classic RK4 step: for one drone in plain floats, and for n.

One drone (QuadrotorSim) keeps a flat list of 17 floats, in this order: position (3, world, m),
velocity (3, world, m/s), attitude quaternion (w, x, y, z), body rates (3, body, rad/s), rotor
speeds (4, rad/s). Plain floats rather than numpy arrays: at this size numpy's per-call overhead
dominates, and the step runs several times faster without it.

n drones (QuadrotorBatch) keep a float64 array of shape (STATE_ROWS, n), one column per drone,
rows: velocity, body rates, position, quaternion, rotor speeds, and a row of constant ones that
lets the derivative build every product term with one gather.

Both codings evaluate the same expressions, in the same order, with the same constants (from
RigidBodyModel), using only +, -, *, /, sqrt, min and max, which IEEE 754 rounds correctly in
numpy and in Python alike. Each batched pass below says which scalar line it mirrors. So a
column of a batch steps bit for bit as a QuadrotorSim with the same inputs does, whatever n, its
position or the other columns: every batched operation is elementwise across columns (no
reduction across drones, no BLAS), and numpy's transcendental functions, whose SIMD and scalar
paths need not agree to the last bit, are not used.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np

from sim.quadrotor.params import QuadrotorParams
from sim.types import FloatArray

STATE_SIZE = 17
"""Length of one drone's flat state: p, v, q, w, rotors."""
Vector = list[float]
NO_NOISE = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)

VEL, RATES, POS, QUAT, ROTORS = slice(0, 3), slice(3, 6), slice(6, 9), slice(9, 13), slice(13, 17)
"""Rows of the batch state."""
ONES_ROW = 17
STATE_ROWS = 18
FLAT_TO_ROWS = [6, 7, 8, 0, 1, 2, 9, 10, 11, 12, 3, 4, 5, 13, 14, 15, 16]
"""The batch row of each entry of the flat state: state[FLAT_TO_ROWS, col] is drone col's flat state."""
_CORE = slice(0, 13)  # what the coupled RK4 stages carry: velocity, rates, position, quaternion

RotorStep = Callable[[FloatArray, FloatArray], None]
"""rk4(rotor_cmd (4, n) rad/s, noise (6, n)): one step from the bound state into the bound output."""

_add, _sub, _mul, _div, _sqrt = np.add, np.subtract, np.multiply, np.divide, np.sqrt


class RigidBodyModel:
    """Per-vehicle constants the derivative needs, pre-combined once, for both codings."""

    __slots__ = (
        "_stages",
        "drag_per_mass",
        "drag_per_mass_sq",
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
        self.drag_per_mass_sq = self.drag_per_mass * self.drag_per_mass
        self.motor_rate = 1.0 / p.motor_time_constant_s
        self._stages: dict[float, tuple[float, float, float, float]] = {}

    def rotor_stages(self, h: float) -> tuple[float, float, float, float]:
        """(b2, b3, b4, phi) of RK4 on the linear motor lag r_dot = rate (c - r) with c held over h:
        stage i sees r + b_i (c - r) (b1 = 0), and the step ends at r + phi (c - r). This is RK4
        itself, written out for a linear equation; it is computed once per step length."""
        stages = self._stages.get(h)
        if stages is None:
            hk = h * self.motor_rate
            b2 = 0.5 * hk
            b3 = 0.5 * hk * (1.0 - b2)
            b4 = hk * (1.0 - b3)
            phi = hk / 6.0 * (1.0 + 2.0 * (1.0 - b2) + 2.0 * (1.0 - b3) + (1.0 - b4))
            stages = self._stages[h] = (b2, b3, b4, phi)
        return stages


# ---------------------------------------------------------------------------------------------
# One drone, plain floats.


def _derivative(
    c: Sequence[float],
    r1: float,
    r2: float,
    r3: float,
    r4: float,
    noise: Sequence[float],
    lz: float,
    m: RigidBodyModel,
) -> Vector:
    """d/dt of the first 13 entries (p, v, q, w) for the stage's rotor speeds r, the process noise
    and lz = noise z - g."""
    _, _, _, vx, vy, vz, qw, qx, qy, qz, wx, wy, wz = c
    s1, s2, s3, s4 = r1 * r1, r2 * r2, r3 * r3, r4 * r4
    thrust = m.thrust_per_mass * (s1 + s2 + s3 + s4)
    hw, hx, hy, hz = 0.5 * qw, 0.5 * qx, 0.5 * qy, 0.5 * qz
    dw, dx, dy = 2.0 * qw, 2.0 * qx, 2.0 * qy
    d2 = m.drag_per_mass_sq
    drag = math.sqrt(d2 * vx * vx + d2 * vy * vy + d2 * vz * vz)  # drag/m * |v|
    return [
        vx,
        vy,
        vz,
        # Thrust along the body z axis in the world frame (third column of R(q)), drag, gravity, noise.
        thrust * (dx * qz + dw * qy) - drag * vx + noise[0],
        thrust * (dy * qz - dw * qx) - drag * vy + noise[1],
        thrust * (1.0 - dx * qx - dy * qy) - drag * vz + lz,
        # q_dot = 0.5 * q (x) (0, w), Hamilton product.
        -(hx * wx) - hy * wy - hz * wz,
        hw * wx + hy * wz - hz * wy,
        hw * wy + hz * wx - hx * wz,
        hw * wz + hx * wy - hy * wx,
        # Moments of the rotors over the inertia, angular noise, then the gyroscopic term.
        m.roll_gain * (s1 + s2 - s3 - s4) + noise[3] + m.gyro_x * wy * wz,
        m.pitch_gain * (s2 + s3 - s1 - s4) + noise[4] + m.gyro_y * wz * wx,
        m.yaw_gain * (s2 + s4 - s1 - s3) + noise[5] + m.gyro_z * wx * wy,
    ]


def rk4_step(
    s: Sequence[float], rotor_cmd: Sequence[float], m: RigidBodyModel, noise: Sequence[float], h: float
) -> Vector:
    """One classic fourth-order Runge-Kutta step of length h (s) of a flat state, inputs held constant.

    noise is (linear accel x, y, z in m/s^2, angular accel x, y, z in rad/s^2).
    """
    b2, b3, b4, phi = m.rotor_stages(h)
    r1, r2, r3, r4 = s[13], s[14], s[15], s[16]
    c1, c2, c3, c4 = rotor_cmd
    e1, e2, e3, e4 = c1 - r1, c2 - r2, c3 - r3, c4 - r4
    lz = noise[2] - m.g
    half = 0.5 * h
    core = s[:13]
    k1 = _derivative(core, r1, r2, r3, r4, noise, lz, m)
    stage = [a + half * b for a, b in zip(core, k1, strict=True)]
    k2 = _derivative(stage, r1 + e1 * b2, r2 + e2 * b2, r3 + e3 * b2, r4 + e4 * b2, noise, lz, m)
    stage = [a + half * b for a, b in zip(core, k2, strict=True)]
    k3 = _derivative(stage, r1 + e1 * b3, r2 + e2 * b3, r3 + e3 * b3, r4 + e4 * b3, noise, lz, m)
    stage = [a + h * b for a, b in zip(core, k3, strict=True)]
    k4 = _derivative(stage, r1 + e1 * b4, r2 + e2 * b4, r3 + e3 * b4, r4 + e4 * b4, noise, lz, m)
    sixth = h / 6.0
    out = [a + sixth * (b + 2.0 * (c + d) + e) for a, b, c, d, e in zip(core, k1, k2, k3, k4, strict=True)]
    out += (r1 + e1 * phi, r2 + e2 * phi, r3 + e3 * phi, r4 + e4 * phi)
    return out


def normalize_quaternion(s: Vector) -> None:
    """Rescale the attitude quaternion (indices 6-9) of a flat state to unit length, in place."""
    qw, qx, qy, qz = s[6], s[7], s[8], s[9]
    norm = math.sqrt(qw * qw + qx * qx + qy * qy + qz * qz)
    s[6], s[7], s[8], s[9] = qw / norm, qx / norm, qy / norm, qz / norm


# ---------------------------------------------------------------------------------------------
# n drones, numpy columns: the same operations in the same order.


def _sums_of_products(m: RigidBodyModel) -> tuple[list[int], list[int], list[float]]:
    """Rows a, b and coefficient c of the products (s[a] * c) * s[b] in _derivative.

    The first 39 terms are 13 sums of three, stored term-major (term t of sum g at t * 13 + g) so
    that each sum is two adds of contiguous blocks, added left to right as _derivative does:
    p_dot (3), q_dot (4), the body z axis in the world frame (3), and three copies of
    (drag/m)^2 |v|^2. The last 3 are the gyroscopic terms. A coefficient of ±0.5 or ±2 gives
    exactly _derivative's hw, dx, ... (and their negations); a padding term is -0.0, which added
    to anything leaves it unchanged, sign of zero included.
    """
    vx, vy, vz, wx, wy, wz = range(6)
    qw, qx, qy, qz, one = 9, 10, 11, 12, ONES_ROW
    pad = (one, one, -0.0)
    d2 = m.drag_per_mass_sq
    speed_sq = [(vx, vx, d2), (vy, vy, d2), (vz, vz, d2)]
    sums = [
        [(vx, one, 1.0), pad, pad],  # p_dot = v
        [(vy, one, 1.0), pad, pad],
        [(vz, one, 1.0), pad, pad],
        [(qx, wx, -0.5), (qy, wy, -0.5), (qz, wz, -0.5)],  # -(hx wx) - hy wy - hz wz
        [(qw, wx, 0.5), (qy, wz, 0.5), (qz, wy, -0.5)],
        [(qw, wy, 0.5), (qz, wx, 0.5), (qx, wz, -0.5)],
        [(qw, wz, 0.5), (qx, wy, 0.5), (qy, wx, -0.5)],
        [(qx, qz, 2.0), (qw, qy, 2.0), pad],  # dx qz + dw qy
        [(qy, qz, 2.0), (qw, qx, -2.0), pad],  # dy qz - dw qx
        [(one, one, 1.0), (qx, qx, -2.0), (qy, qy, -2.0)],  # 1 - dx qx - dy qy
        speed_sq,
        speed_sq,
        speed_sq,
    ]
    terms = [group[t] for t in range(3) for group in sums]
    terms += [(wy, wz, m.gyro_x), (wz, wx, m.gyro_y), (wx, wy, m.gyro_z)]
    return [t[0] for t in terms], [t[1] for t in terms], [t[2] for t in terms]


# _derivative's thrust and moments as four signed squared rotor speeds, in its order of addition:
# thrust (three copies, so that it multiplies the body axis block without broadcasting), roll,
# pitch, yaw. Rotors are numbered from 0 here.
_FORCE_TERMS = [((0, 1.0), (1, 1.0), (2, 1.0), (3, 1.0))] * 3 + [
    ((0, 1.0), (1, 1.0), (2, -1.0), (3, -1.0)),  # s1 + s2 - s3 - s4
    ((1, 1.0), (2, 1.0), (0, -1.0), (3, -1.0)),  # s2 + s3 - s1 - s4
    ((1, 1.0), (3, 1.0), (0, -1.0), (2, -1.0)),  # s2 + s4 - s1 - s3
]


def _force_table(m: RigidBodyModel) -> tuple[list[int], list[float], list[float]]:
    """For the 24 force rows (stage * 6 + output): the gather rows and signs of their four terms,
    term-major like _sums_of_products (source row = stage * 4 + rotor), and each row's gain."""
    index, sign = [], []
    for t in range(4):
        for stage in range(4):
            for terms in _FORCE_TERMS:
                rotor, signed = terms[t]
                index.append(stage * 4 + rotor)
                sign.append(signed)
    gains = [m.thrust_per_mass] * 3 + [m.roll_gain, m.pitch_gain, m.yaw_gain]
    return index, sign, gains * 4


def _full(values: list[float], n: int) -> FloatArray:
    """A constant per row, repeated across n columns: same-shape operands keep numpy on its fast path."""
    return np.repeat(np.array(values, dtype=float)[:, None], n, axis=1)


def bind_rk4(model: RigidBodyModel, h: float, state: FloatArray, out: FloatArray) -> RotorStep:
    """rk4_step for every column: one step of length h (s) from state into out, both (STATE_ROWS, n).

    The rotor lag is linear and depends on nothing else, so its four stage values are formed at
    once and turned into the four stages' forces; the coupled rigid body then takes the four
    stages. Buffers and views are made here, once, so a step is a fixed list of numpy calls, each
    on contiguous arrays of one shape: broadcasting and strided views cost several times more.
    """
    n = state.shape[1]
    rows_a, rows_b, coefs = _sums_of_products(model)
    idx_a, idx_b, coef = np.array(rows_a, dtype=np.intp), np.array(rows_b, dtype=np.intp), _full(coefs, n)
    ga, gb = np.empty((42, n)), np.empty((42, n))
    term0, term1, term2, gyro = ga[0:13], ga[13:26], ga[26:39], ga[39:42]
    k = np.empty((4, 19, n))  # per stage: v_dot, w_dot, p_dot, q_dot, body z axis, drag/m |v| (x3)
    stage = np.empty((STATE_ROWS, n))
    stage[ONES_ROW] = 1.0
    stage_core, state_core = stage[_CORE], state[_CORE]
    b2, b3, b4, phi = model.rotor_stages(h)
    rotors, out_rotors = state[ROTORS], out[ROTORS]
    err4, tmp16, tmp4 = np.empty((4, n)), np.empty((16, n)), np.empty((4, n))
    b16, phi4 = _full([b for b in (0.0, b2, b3, b4) for _ in range(4)], n), _full([phi] * 4, n)
    rotor_rep, err_rep = np.arange(16, dtype=np.intp) % 4 + ROTORS.start, np.arange(16, dtype=np.intp) % 4
    squares = np.empty((16, n))  # stage rotor speeds, then their squares (stage * 4 + rotor)
    force_rows, force_signs, force_gains = _force_table(model)
    force_idx, sign96, gain24 = (
        np.array(force_rows, dtype=np.intp),
        _full(force_signs, n),
        _full(force_gains, n),
    )
    gf = np.empty((96, n))
    f_terms = [gf[24 * t : 24 * (t + 1)] for t in range(4)]
    force = np.empty((4, 6, n))  # per stage: thrust/m (x3), angular accelerations
    force_flat = force.reshape(24, n)
    force_noise = np.full((4, 6, n), -0.0)  # -0.0 for the thrust rows, the angular noise after
    force_noise_flat, noise_ang = force_noise.reshape(24, n), force_noise[:, 3:6]
    gravity = _full([0.0, 0.0, model.g], n)
    lin, tmp3, acc = np.empty((3, n)), np.empty((3, n)), np.empty((13, n))
    half13, h13, sixth13, two13 = (_full([c] * 13, n) for c in (0.5 * h, h, h / 6.0, 2.0))
    sources = (state, stage, stage, stage)
    stages = [
        (
            src,
            src[VEL],
            force[i, 0:3],
            force[i, 3:6],
            k[i, 0:3],
            k[i, 3:6],
            k[i, 6:19],
            k[i, 13:16],
            k[i, 16:19],
        )
        for i, src in enumerate(sources)
    ]
    k_core = [k[i, _CORE] for i in range(4)]

    def derivative(
        src: FloatArray,
        src_v: FloatArray,
        thrust: FloatArray,
        angular: FloatArray,
        k_v: FloatArray,
        k_w: FloatArray,
        k_sums: FloatArray,
        k_b: FloatArray,
        drag: FloatArray,
    ) -> None:
        # _derivative: every product (s[a] * c) * s[b], then the sums of three left to right.
        src.take(idx_a, 0, ga, "clip")
        src.take(idx_b, 0, gb, "clip")
        _mul(ga, coef, ga)
        _mul(ga, gb, ga)
        _add(term0, term1, k_sums)
        _add(k_sums, term2, k_sums)
        _add(angular, gyro, k_w)  # (roll_gain * (...) + noise) + gyro_x wy wz
        _sqrt(drag, drag)  # drag/m * |v|, once per axis
        _mul(thrust, k_b, k_v)  # thrust * b - drag * v + noise
        _mul(drag, src_v, tmp3)
        _sub(k_v, tmp3, k_v)
        _add(k_v, lin, k_v)

    def rk4(rotor_cmd: FloatArray, noise: FloatArray) -> None:
        # e = c - r; stage rotor speeds r + e * b_i, squared.
        _sub(rotor_cmd, rotors, err4)
        state.take(rotor_rep, 0, squares, "clip")
        err4.take(err_rep, 0, tmp16, "clip")
        _mul(tmp16, b16, tmp16)
        _add(squares, tmp16, squares)
        _mul(squares, squares, squares)
        # The four stages' thrust/m and moments: signed sums of squares, times the gain, plus angular
        # noise (and -0.0 for the thrust), in _derivative's order.
        squares.take(force_idx, 0, gf, "clip")
        _mul(gf, sign96, gf)
        _add(f_terms[0], f_terms[1], force_flat)
        _add(force_flat, f_terms[2], force_flat)
        _add(force_flat, f_terms[3], force_flat)
        _mul(force_flat, gain24, force_flat)
        np.copyto(noise_ang, noise[3:6])
        _add(force_flat, force_noise_flat, force_flat)
        _sub(noise[0:3], gravity, lin)  # (noise x - 0, noise y - 0, noise z - g): noise x, y and lz
        # The stages: a + half * k, a + half * k, a + h * k.
        derivative(*stages[0])
        _mul(k_core[0], half13, stage_core)
        _add(stage_core, state_core, stage_core)
        derivative(*stages[1])
        _mul(k_core[1], half13, stage_core)
        _add(stage_core, state_core, stage_core)
        derivative(*stages[2])
        _mul(k_core[2], h13, stage_core)
        _add(stage_core, state_core, stage_core)
        derivative(*stages[3])
        # a + sixth * (b + 2 (c + d) + e), and the rotors r + e * phi.
        _add(k_core[1], k_core[2], acc)
        _mul(acc, two13, acc)
        _add(acc, k_core[0], acc)
        _add(acc, k_core[3], acc)
        _mul(acc, sixth13, acc)
        _add(state_core, acc, out[_CORE])
        _mul(err4, phi4, tmp4)
        _add(rotors, tmp4, out_rotors)

    return rk4


def normalize_quaternions(quat: FloatArray, norm: FloatArray, squares: FloatArray) -> None:
    """normalize_quaternion for each column of quat (4, n) in place; norm (n,) and squares (4, n) are scratch."""
    _mul(quat, quat, squares)
    _add(squares[0], squares[1], norm)
    _add(norm, squares[2], norm)
    _add(norm, squares[3], norm)
    _sqrt(norm, norm)
    _div(quat, norm, quat)
