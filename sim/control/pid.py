"""The lab's scalar PID (lab reference §3.4), with optional limits the lab does not have."""

from __future__ import annotations

import math


class PID:
    """u = kp*e + ki*I + kd*D with e = setpoint - measured, I += e*dt, D = (e - e_prev)/dt.

    e_prev starts at 0, so with kd != 0 the first update after a reset kicks, as in the lab.
    integral_limit bounds |I| (anti-windup); output_limit bounds |u|. None means unbounded.
    """

    def __init__(
        self,
        kp: float,
        ki: float = 0.0,
        kd: float = 0.0,
        *,
        integral_limit: float | None = None,
        output_limit: float | None = None,
    ) -> None:
        for name, value in (("kp", kp), ("ki", ki), ("kd", kd)):
            if not math.isfinite(value):
                raise ValueError(f"PID {name} must be finite, got {value}")
        for name, limit in (("integral_limit", integral_limit), ("output_limit", output_limit)):
            if limit is not None and not limit >= 0:
                raise ValueError(f"PID {name} must be >= 0 or None, got {limit}")
        self.kp, self.ki, self.kd = float(kp), float(ki), float(kd)
        self.integral_limit = integral_limit
        self.output_limit = output_limit
        self.reset()

    def reset(self) -> None:
        """Forget the integral and the previous error."""
        self.integral = 0.0
        self.prev_error = 0.0

    def update(self, setpoint: float, measured: float, dt_s: float) -> float:
        """One controller tick of length dt_s (s)."""
        if not dt_s > 0:
            raise ValueError(f"dt_s must be > 0, got {dt_s}")
        error = setpoint - measured
        self.integral += error * dt_s
        if self.integral_limit is not None:
            self.integral = min(max(self.integral, -self.integral_limit), self.integral_limit)
        derivative = (error - self.prev_error) / dt_s
        output = self.kp * error + self.ki * self.integral + self.kd * derivative
        self.prev_error = error
        if self.output_limit is not None:
            output = min(max(output, -self.output_limit), self.output_limit)
        return output
