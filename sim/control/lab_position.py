"""The lab's simple-mode position controller (PositionControllerNode, lab reference §3.4)."""

from __future__ import annotations

from sim.control.pid import PID
from sim.quadrotor.state import as_finite_floats
from sim.types import FloatsLike

LAB_PID_DT_S = 0.01
"""The PID's dt: always 0.01 s in the lab, whatever the timer period (0.01 s in Lab 2, 0.02 s later)."""
LAB_DEFAULT_SETPOINT_M = (0.0, 0.0, 3.0)
SETPOINT_CHANGE_THRESHOLD_M = 1e-6


class LabPositionController:
    """Three independent PIDs mapping GPS position (m) to a velocity command (m/s), no saturation.

    Effective Lab 2 gains are Kp=1, Ki=0, Kd=0 (the launch parameter names did not match).
    """

    def __init__(
        self,
        kp: float = 1.0,
        ki: float = 0.0,
        kd: float = 0.0,
        setpoint_m: FloatsLike = LAB_DEFAULT_SETPOINT_M,
    ) -> None:
        self.pids = (PID(kp, ki, kd), PID(kp, ki, kd), PID(kp, ki, kd))
        self.setpoint_m = as_finite_floats("setpoint_m", setpoint_m, 3)

    def set_setpoint(self, setpoint_m: FloatsLike) -> None:
        """A /uav/input/position message: if any axis moved by > 1e-6 m, reset all PIDs and take it."""
        new = as_finite_floats("setpoint_m", setpoint_m, 3)
        if any(abs(a - b) > SETPOINT_CHANGE_THRESHOLD_M for a, b in zip(new, self.setpoint_m, strict=True)):
            for pid in self.pids:
                pid.reset()
            self.setpoint_m = new

    def update(
        self, measured_position_m: FloatsLike, dt_s: float = LAB_PID_DT_S
    ) -> tuple[float, float, float]:
        """One timer tick: the velocity command (m/s) for the latest GPS position."""
        measured = as_finite_floats("measured_position_m", measured_position_m, 3)
        vx, vy, vz = (
            pid.update(sp, m, dt_s) for pid, sp, m in zip(self.pids, self.setpoint_m, measured, strict=True)
        )
        return vx, vy, vz
