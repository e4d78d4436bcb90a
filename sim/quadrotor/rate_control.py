"""The on-board body-rate loop and mixer that turn a rateThrust command into rotor speeds.

Follows the FlightGoggles dynamics node (lab reference §4, steps 1-2). It runs once per
physics step, so its output is held constant across the RK4 sub-stages.
"""

from __future__ import annotations

import math

from sim.quadrotor.params import QuadrotorParams


class RateLoop:
    """alpha_cmd = kp*(w_cmd - w_f) + ki*int(w_cmd - w_f) - kd*dw_f/dt, then M = I*alpha_cmd, then the mixer.

    w_f is the measured body rate after an optional second-order low-pass filter; without
    the filter dw_f/dt is a backward difference.
    """

    def __init__(self, p: QuadrotorParams) -> None:
        self._p = p
        self._ix, self._iy, self._iz = p.inertia_kg_m2
        self._kp, self._ki, self._kd = p.rate_kp_1_s, p.rate_ki_1_s2, p.rate_kd
        self._i_max = p.rate_integral_limit_rad
        omega_n = 2.0 * math.pi * p.rate_filter_cutoff_hz
        self._filter_p = omega_n * omega_n
        self._filter_q = 2.0 * p.rate_filter_damping * omega_n
        k_t = p.thrust_coeff_n_per_rad_s2
        self._per_thrust = 1.0 / (4.0 * k_t)
        self._per_roll_pitch = 1.0 / (4.0 * p.arm_length_m * k_t)
        self._per_yaw = 1.0 / (4.0 * p.torque_coeff_nm_per_rad_s2)
        self._max_sq = p.max_rotor_speed_rad_s**2
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
        self, rates: list[float], rates_cmd: tuple[float, float, float], thrust_n: float, dt: float
    ) -> tuple[float, float, float, float]:
        """Rotor-speed commands (rad/s) for measured rates, commanded rates and thrust."""
        self._filter(rates, dt)
        f, fd, integral = self._filtered, self._filtered_dot, self._integral
        kp, ki, kd, i_max = self._kp, self._ki, self._kd, self._i_max
        alpha = [0.0, 0.0, 0.0]
        for axis in range(3):
            error = rates_cmd[axis] - f[axis]
            acc = integral[axis] + error * dt
            integral[axis] = min(max(acc, -i_max), i_max)
            alpha[axis] = kp * error + ki * integral[axis] - kd * fd[axis]
        return self.mix(self._ix * alpha[0], self._iy * alpha[1], self._iz * alpha[2], thrust_n)

    def mix(self, mx: float, my: float, mz: float, thrust_n: float) -> tuple[float, float, float, float]:
        """Rotor speeds (rad/s) for body moments (N*m) and thrust (N); motor 1 front-left, CCW."""
        base = thrust_n * self._per_thrust
        roll, pitch, yaw = mx * self._per_roll_pitch, my * self._per_roll_pitch, mz * self._per_yaw
        top = self._max_sq
        squares = (
            base + roll - pitch - yaw,
            base + roll + pitch + yaw,
            base - roll + pitch - yaw,
            base - roll - pitch + yaw,
        )
        # A rotor cannot spin backwards or past its limit; the clamp is where saturation happens.
        c1, c2, c3, c4 = (math.sqrt(min(max(v, 0.0), top)) for v in squares)
        return c1, c2, c3, c4

    def _filter(self, rates: list[float], dt: float) -> None:
        if not self._p.rate_filter_enabled:
            prev = self._filtered
            self._filtered_dot = [(r - p) / dt for r, p in zip(rates, prev, strict=True)]
            self._filtered = [rates[0], rates[1], rates[2]]
            return
        # Backward-Euler step of x'' = P (u - x) - Q x': unconditionally stable at any dt.
        denom = 1.0 + dt * self._filter_q + dt * dt * self._filter_p
        gain = dt * self._filter_p
        for axis in range(3):
            x, v = self._filtered[axis], self._filtered_dot[axis]
            v = (v + gain * (rates[axis] - x)) / denom
            self._filtered_dot[axis] = v
            self._filtered[axis] = x + dt * v
