"""The on-board body-rate loop and mixer that turn a rateThrust command into rotor speeds.

Follows the FlightGoggles dynamics node (lab reference §4, steps 1-2). It runs once per
physics step, so its output is held constant across the RK4 stages. RateLoop runs it for one
drone in plain floats; bind_rate_loop for n drones in numpy columns, with the same constants
(RateGains) and the same operations in the same order (see sim.quadrotor.dynamics).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from sim.quadrotor.params import QuadrotorParams
from sim.types import FloatArray

_add, _sub, _mul, _div, _sqrt = np.add, np.subtract, np.multiply, np.divide, np.sqrt
_max, _min = np.maximum, np.minimum

# Sign of the roll, pitch and yaw share in each rotor's squared speed; motor 1 front-left, CCW.
MIX_SIGNS = ((1.0, -1.0, -1.0), (1.0, 1.0, 1.0), (-1.0, 1.0, -1.0), (-1.0, -1.0, 1.0))


class RateGains:
    """The loop's constants, pre-combined once. The gains are pre-multiplied by the inertia and the
    mixer's scale, so the loop yields each axis's share of the squared rotor speeds directly:
    share = kp*e + ki*int(e) - kd*dw_f/dt, with the gains per axis."""

    __slots__ = (
        "filter_denom",
        "filter_enabled",
        "filter_gain",
        "integral_limit",
        "kd",
        "ki",
        "kp",
        "max_sq",
        "per_moment",
        "per_thrust",
    )

    def __init__(self, p: QuadrotorParams, dt_s: float) -> None:
        k_t, k_q, arm = p.thrust_coeff_n_per_rad_s2, p.torque_coeff_nm_per_rad_s2, p.arm_length_m
        self.per_thrust = 1.0 / (4.0 * k_t)
        """Squared rotor speed per newton of collective thrust, (rad/s)^2 / N."""
        per_roll_pitch = 1.0 / (4.0 * arm * k_t)
        self.per_moment = (per_roll_pitch, per_roll_pitch, 1.0 / (4.0 * k_q))
        """Squared rotor speed per N*m of roll, pitch and yaw moment."""
        scale = [i * m for i, m in zip(p.inertia_kg_m2, self.per_moment, strict=True)]
        self.kp, self.ki, self.kd = (
            (g * scale[0], g * scale[1], g * scale[2]) for g in (p.rate_kp_1_s, p.rate_ki_1_s2, p.rate_kd)
        )
        self.integral_limit = p.rate_integral_limit_rad
        self.max_sq = p.max_rotor_speed_rad_s**2
        self.filter_enabled = p.rate_filter_enabled
        # Backward-Euler step of x'' = P (u - x) - Q x': unconditionally stable at any dt.
        omega_n = 2.0 * math.pi * p.rate_filter_cutoff_hz
        filter_p, filter_q = omega_n * omega_n, 2.0 * p.rate_filter_damping * omega_n
        self.filter_denom = 1.0 + dt_s * filter_q + dt_s * dt_s * filter_p
        self.filter_gain = dt_s * filter_p


class RateLoop:
    """alpha_cmd = kp*(w_cmd - w_f) + ki*int(w_cmd - w_f) - kd*dw_f/dt, then M = I*alpha_cmd, then the mixer.

    w_f is the measured body rate after an optional second-order low-pass filter; without
    the filter dw_f/dt is a backward difference. One drone, at a fixed step dt_s.
    """

    def __init__(self, p: QuadrotorParams, dt_s: float = 0.001) -> None:
        self.gains = RateGains(p, dt_s)
        self._dt = dt_s
        self.reset()

    def reset(self, rates_rad_s: tuple[float, float, float] = (0.0, 0.0, 0.0)) -> None:
        """Forget the integral and settle the filter on the given measured rates."""
        self._filtered = list(rates_rad_s)
        self._filtered_dot = [0.0, 0.0, 0.0]
        self._integral = [0.0, 0.0, 0.0]

    def reset_integral(self) -> None:
        """Zero the integral, as a flight controller's land detector does while landed."""
        self._integral = [0.0, 0.0, 0.0]

    def rotor_commands(
        self, rates: list[float], rates_cmd: tuple[float, float, float], base: float
    ) -> tuple[float, float, float, float]:
        """Rotor-speed commands (rad/s) for measured rates, commanded rates and the thrust's share
        of the squared rotor speeds (thrust N times gains.per_thrust)."""
        g, dt = self.gains, self._dt
        f, fd, integral = self._filtered, self._filtered_dot, self._integral
        w1, w2, w3 = rates[0], rates[1], rates[2]
        if g.filter_enabled:
            denom, gain = g.filter_denom, g.filter_gain
            fd[0] = v1 = (fd[0] + gain * (w1 - f[0])) / denom
            fd[1] = v2 = (fd[1] + gain * (w2 - f[1])) / denom
            fd[2] = v3 = (fd[2] + gain * (w3 - f[2])) / denom
            f[0], f[1], f[2] = f[0] + dt * v1, f[1] + dt * v2, f[2] + dt * v3
        else:
            fd[0], fd[1], fd[2] = (w1 - f[0]) / dt, (w2 - f[1]) / dt, (w3 - f[2]) / dt
            f[0], f[1], f[2] = w1, w2, w3
        top = g.integral_limit
        kp, ki, kd = g.kp, g.ki, g.kd
        e1, e2, e3 = rates_cmd[0] - f[0], rates_cmd[1] - f[1], rates_cmd[2] - f[2]
        i1, i2, i3 = integral[0] + e1 * dt, integral[1] + e2 * dt, integral[2] + e3 * dt
        # min(max(i, -top), top), written out: max(a, b) is a unless b > a, min(a, b) is a unless b < a.
        i1 = -top if -top > i1 else (top if top < i1 else i1)
        i2 = -top if -top > i2 else (top if top < i2 else i2)
        i3 = -top if -top > i3 else (top if top < i3 else i3)
        integral[0], integral[1], integral[2] = i1, i2, i3
        return _mix(
            e1 * kp[0] + i1 * ki[0] - fd[0] * kd[0],
            e2 * kp[1] + i2 * ki[1] - fd[1] * kd[1],
            e3 * kp[2] + i3 * ki[2] - fd[2] * kd[2],
            base,
            g.max_sq,
        )

    def mix(self, mx: float, my: float, mz: float, thrust_n: float) -> tuple[float, float, float, float]:
        """Rotor speeds (rad/s) for body moments (N*m) and thrust (N); motor 1 front-left, CCW."""
        per, g = self.gains.per_moment, self.gains
        return _mix(mx * per[0], my * per[1], mz * per[2], thrust_n * g.per_thrust, g.max_sq)


def _mix(roll: float, pitch: float, yaw: float, base: float, top: float) -> tuple[float, float, float, float]:
    """Rotor speeds for the roll, pitch and yaw shares and the thrust share of the squared speeds."""
    sqrt = math.sqrt
    v1 = base + roll - pitch - yaw
    v2 = base + roll + pitch + yaw
    v3 = base - roll + pitch - yaw
    v4 = base - roll - pitch + yaw
    # A rotor cannot spin backwards or past its limit; the clamp is where saturation happens:
    # sqrt(min(max(v, 0.0), top)), written out as in rotor_commands.
    return (
        sqrt(0.0 if v1 < 0.0 else (top if top < v1 else v1)),
        sqrt(0.0 if v2 < 0.0 else (top if top < v2 else v2)),
        sqrt(0.0 if v3 < 0.0 else (top if top < v3 else v3)),
        sqrt(0.0 if v4 < 0.0 else (top if top < v4 else v4)),
    )


def bind_rate_loop(
    gains: RateGains,
    dt_s: float,
    rates: FloatArray,
    filtered: FloatArray,
    filtered_dot: FloatArray,
    integral: FloatArray,
    rates_cmd: FloatArray,
    shares_and_base: FloatArray,
    out: FloatArray,
) -> Callable[[], None]:
    """RateLoop.rotor_commands for every column: measured rates (3, n) and the loop's state
    (filtered, filtered_dot, integral, (3, n) each, updated in place), commanded rates (3, n) ->
    rotor speeds out (4, n). shares_and_base (4, n): rows 0-2 are scratch for the shares, row 3
    holds each drone's thrust share."""
    n = rates.shape[1]
    kp, ki, kd = (np.repeat(np.array(k)[:, None], n, axis=1) for k in (gains.kp, gains.ki, gains.kd))
    i_max, i_min = np.array(gains.integral_limit), np.array(-gains.integral_limit)
    error, tmp, shares = np.empty((3, n)), np.empty((3, n)), shares_and_base[0:3]
    mixer = _bind_mixer(gains.max_sq, shares_and_base, out)
    filter_on = gains.filter_enabled
    denom, gain, dt = np.array(gains.filter_denom), np.array(gains.filter_gain), np.array(dt_s)

    def rate_loop() -> None:
        if filter_on:
            _sub(rates, filtered, tmp)  # (fd + gain * (rate - x)) / denom
            _mul(tmp, gain, tmp)
            _add(tmp, filtered_dot, tmp)
            _div(tmp, denom, filtered_dot)
            _mul(filtered_dot, dt, tmp)  # x + dt * v
            _add(filtered, tmp, filtered)
        else:
            _sub(rates, filtered, filtered_dot)
            _div(filtered_dot, dt, filtered_dot)
            np.copyto(filtered, rates)
        _sub(rates_cmd, filtered, error)
        _mul(error, dt, tmp)  # min(max(integral + error * dt, -top), top)
        _add(integral, tmp, integral)
        _max(integral, i_min, out=integral)
        _min(integral, i_max, out=integral)
        _mul(error, kp, shares)  # error * kp + i * ki - fd * kd
        _mul(integral, ki, tmp)
        _add(shares, tmp, shares)
        _mul(filtered_dot, kd, tmp)
        _sub(shares, tmp, shares)
        mixer()

    return rate_loop


def _bind_mixer(max_sq: float, shares_and_base: FloatArray, out: FloatArray) -> Callable[[], None]:
    """_mix for every column: rotor speeds into out (4, n) from the shares (rows 0-2) and the thrust
    share (row 3) of shares_and_base, as base ± roll ± pitch ± yaw added left to right."""
    n = out.shape[1]
    order = (3, 0, 1, 2)  # base, roll, pitch, yaw
    index = np.array([order[t] for t in range(4) for _ in range(4)], dtype=np.intp)
    signs = [1.0 if t == 0 else MIX_SIGNS[motor][t - 1] for t in range(4) for motor in range(4)]
    sign16 = np.repeat(np.array(signs)[:, None], n, axis=1)
    terms, squares = np.empty((16, n)), np.empty((4, n))
    t0, t1, t2, t3 = terms[0:4], terms[4:8], terms[8:12], terms[12:16]
    zero, top = np.array(0.0), np.array(max_sq)

    def mixer() -> None:
        shares_and_base.take(index, 0, terms, "clip")
        _mul(terms, sign16, terms)
        _add(t0, t1, squares)
        _add(squares, t2, squares)
        _add(squares, t3, squares)
        # A rotor cannot spin backwards or past its limit; the clamp is where saturation happens.
        _max(squares, zero, out=squares)
        _min(squares, top, out=squares)
        _sqrt(squares, out)

    return mixer
